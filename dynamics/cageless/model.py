"""CagelessBearing: the model's data, its packing into numba arguments, the quasi-static start.

Part of :mod:`lubedyn.dynamics.cageless` (the package docstring gives the overview)."""
from __future__ import annotations

import logging

from dataclasses import dataclass, fields
from typing import ClassVar
import math

import numpy as np

from lubedyn.lubrication.errors import did_you_mean
from lubedyn.lubrication.laws import bearing as laws_bearing
from lubedyn.lubrication.laws import contact as laws_contact
from lubedyn.lubrication.laws.collision import ball_ball_parameters, ball_ball_row
from lubedyn.lubrication.laws.film import hamrock_dowson_central

from .. import contacts as C
from ..contacts import FILM_KINDS, with_map_ends
from ..errors import DynamicsInputError
from ..groups import fail
from .groups import Bearing, Films, Fidelity, Initial, Operating, Slots
from ..interp import HERMITE, fixed_options
from ..specialise import entry_point
from .kernels import forces, rhs
from .layout import (DOFS, D_AI, D_AO, D_QI, D_QO, MAP_SPEED_AXES, NB_6DOF, NB_PLANAR, N_RING, PARAMETER_DTYPE,
    RACES, SCENARIOS, TRACTIONS, BallBallMap, KernelArgs, MapArrays, TractionMaps, parameter_record)

logger = logging.getLogger(__name__)

# ----------------------------------------------------------------------------- model builder
def _map_arrays(film_map, speed_axis):
    """The :class:`MapArrays` of the map kernel from a force map's kernel arrays ``(axes, logs, values, logv,
    method)`` (:class:`lubedyn.maps.KernelArrays`) on the speed axis ``speed_axis`` (``films.map_speed_axis``;
    None: "squeeze_number"), or from a :class:`BallBallMap` (kernel arrays with their own speed axis; a
    ``speed_axis`` given that differs from it is refused); a two-axis map (gap, speed) gets a constant third
    axis.  ``values``: (8, n0, n1, n2) hermite data, or (n0, n1, n2) values of the linear and pchip methods
    (the kernels choose the reader by this dimension at compile time)."""
    if isinstance(film_map, BallBallMap):
        if speed_axis is not None and speed_axis != film_map.speed_axis:
            raise fail("films.map_speed_axis", speed_axis, f"differs from the film map's own speed axis "
                                                           f"{film_map.speed_axis!r}; leave it out or give that one")
        speed_axis, film_map = film_map.speed_axis, film_map.arrays
    if speed_axis is None:
        speed_axis = "squeeze_number"
    if speed_axis not in MAP_SPEED_AXES:
        raise fail("films.map_speed_axis", speed_axis, f"is not allowed; choose one of {', '.join(MAP_SPEED_AXES)}")
    axis1_kind = MAP_SPEED_AXES[speed_axis]
    try:
        axes, logs, values, logv, method = film_map
    except (TypeError, ValueError):
        raise DynamicsInputError("films.map must be (axes, logs, values, logv, method) of a force map "
                                 "(lubedyn.maps.FilmMap.kernel_arrays('Force [N]'))") from None
    axes = [np.ascontiguousarray(a, dtype=np.float64) for a in axes]
    logs = [int(v) for v in logs]
    vals = np.asarray(values, dtype=np.float64)
    nd = len(axes)
    if nd not in (2, 3) or len(logs) != nd:
        raise DynamicsInputError(f"films.map has {nd} axes; the ball-ball force map needs 2 (gap, speed) or 3 "
                                 "(gap, speed, entrainment speed)")
    shape = tuple(a.size for a in axes)
    hermite = int(method) == HERMITE
    expect = ((2**nd,) if hermite else ()) + shape
    if vals.shape != expect:
        raise DynamicsInputError(f"films.map values have shape {vals.shape}; the axes need {expect}")
    if nd == 2:
        axes.append(np.array([0.0, 1.0]))
        logs.append(0)
        if hermite:  # bit 2 (derivative along the constant axis) is zero
            v3 = np.zeros((8,) + shape + (2,))
            v3[:4] = vals[..., None]
        else:
            v3 = np.repeat(vals[..., None], 2, axis=-1)
        vals = v3
    opts = np.zeros(C.MO_SIZE, dtype=np.int64)
    opts[C.MO_LOG0], opts[C.MO_LOG1], opts[C.MO_LOG2] = logs
    opts[C.MO_LOGV], opts[C.MO_METHOD], opts[C.MO_MODE] = int(logv), int(method), 0
    opts[C.MO_AXIS1] = axis1_kind
    return MapArrays(axes[0], axes[1], axes[2], np.ascontiguousarray(vals), fixed_options(opts))



def _traction_arrays(maps):
    """:class:`TractionMaps` ``(ax0 (2, n0), ax1 (2, n1), ax2 (2, n2), values (2, k, n0, n1, n2), opts)`` from the kernel arrays
    (:class:`lubedyn.maps.KernelArrays` of "Traction coefficient [-]") of the inner and the outer race
    EHL maps, both over (load [N], entrainment speed [m/s], slide-to-roll ratio [-]) with the same
    node counts and method."""
    try:
        (ai, li, vi, lvi, mi), (ao, lo, vo, lvo, mo) = maps
    except (TypeError, ValueError):
        raise DynamicsInputError("model.traction_maps must be (inner, outer) kernel arrays of EHL maps "
                                 "(lubedyn.maps.FilmMap.kernel_arrays('Traction coefficient [-]'))") from None
    if len(ai) != 3 or len(ao) != 3:
        raise DynamicsInputError("traction maps need 3 axes (load, entrainment speed, slide-to-roll ratio)")
    shapes = [tuple(a.size for a in ai), tuple(a.size for a in ao)]
    if shapes[0] != shapes[1] or int(mi) != int(mo) or list(li) != list(lo) or int(lvi) != int(lvo):
        raise DynamicsInputError(f"the inner and outer traction maps differ in nodes {shapes} or method; "
                                 "build both with the same axes")
    if int(lvi) != 0:
        raise DynamicsInputError("traction maps must store the traction coefficient without log (it changes sign)")
    axes = [np.ascontiguousarray(np.stack([ai[k], ao[k]]), dtype=np.float64) for k in range(3)]
    vals = [np.asarray(v, dtype=np.float64) for v in (vi, vo)]
    if int(mi) != HERMITE:
        vals = [v[None] for v in vals]
    opts = np.zeros(C.MO_SIZE, dtype=np.int64)
    opts[C.MO_LOG0], opts[C.MO_LOG1], opts[C.MO_LOG2] = (int(x) for x in li)
    opts[C.MO_LOGV], opts[C.MO_METHOD], opts[C.MO_MODE] = 0, int(mi), 0
    return TractionMaps(axes[0], axes[1], axes[2], np.ascontiguousarray(np.stack(vals)), fixed_options(opts))


@dataclass(frozen=True, kw_only=True)
class CagelessBearing:
    """Cage-less deep-groove ball bearing (SI units), held as six frozen groups, one per table of a
    dynamics case (:mod:`lubedyn.dynamics.cageless.groups`): ``bearing`` (geometry, materials, masses),
    ``operating`` (loads, speed, scenario), ``fidelity`` (the case's ``[model]``: degrees of freedom,
    Hertz constants, damping, traction), ``films`` (the oil, the ball-ball and race films), ``slots``
    and ``initial`` (the starting arrangement and its seeded perturbation).

    The groups carry no paper data as defaults: paper B's come from its parameter set,
    ``lubedyn.papers.zhang2024.parameters.cageless_bearing()`` (Tables 1, 2, 4 and the values it had to
    assume).  Each group checks its own values; :meth:`__post_init__` checks what needs two groups.
    Every error names the case key (``"slots.width = ..."``).
    """

    bearing: Bearing
    operating: Operating
    fidelity: Fidelity = Fidelity()
    films: Films
    slots: Slots
    initial: Initial = Initial()

    #: the group attribute of each case table (``[model]`` is the ``fidelity`` group), and its class
    GROUPS: ClassVar[dict] = {"bearing": "bearing", "operating": "operating", "model": "fidelity",
                              "films": "films", "slots": "slots", "initial": "initial"}
    GROUP_CLASSES: ClassVar[dict] = {"bearing": Bearing, "operating": Operating, "fidelity": Fidelity,
                                     "films": Films, "slots": Slots, "initial": Initial}

    def __post_init__(self):
        for name, cls in self.GROUP_CLASSES.items():
            group = getattr(self, name)
            if isinstance(group, dict):
                object.__setattr__(self, name, cls.build(group))
            elif not isinstance(group, cls):
                raise DynamicsInputError(f"{name} must be a {cls.__name__} (or a dict of its fields), not "
                                         f"{type(group).__name__}", key=cls.TABLE)
        b, sl = self.bearing, self.slots
        if self.fidelity.dof == "planar" and self.operating.axial_load != 0.0:
            raise fail("operating.axial_load", self.operating.axial_load,
                       "N needs model.dof = '6dof' (planar balls stay in the mid-plane and carry no axial load); "
                       "set operating.axial_load = 0 or model.dof = '6dof'")
        if sl.width >= 2.0 * min(b.inner_groove_radius, b.outer_groove_radius):
            raise fail("slots.width", sl.width, "m must be < the groove diameter (2 x the smaller groove radius)")
        D = b.ball_diameter
        dip = 0.5 * D - math.sqrt(0.25 * D * D - 0.25 * sl.width**2) if sl.width < D else 0.5 * D
        if sl.azimuths and dip >= sl.depth:
            raise fail("slots.depth", sl.depth, f"m: a ball dips {dip:g} m into a slot of width {sl.width:g} m and "
                       "would reach the slot floor (not modelled)")

    # derived quantities ------------------------------------------------------
    @property
    def n_balls(self) -> int:
        """Z, the number of balls (it sets the state's size)."""
        return int(self.bearing.n_balls)

    @property
    def mass(self) -> float:
        """Ball mass [kg]."""
        return self.bearing.mass

    @property
    def ball_inertia(self) -> float:
        """2/5 m R^2 [kg m^2]."""
        return 0.4 * self.mass * (0.5 * self.bearing.ball_diameter) ** 2

    @property
    def e_star_race(self) -> float:
        return laws_contact.reduced_modulus(self.bearing.ball_modulus, self.bearing.ball_poisson, self.bearing.ring_modulus, self.bearing.ring_poisson)

    @property
    def e_star_ball(self) -> float:
        return laws_contact.reduced_modulus(self.bearing.ball_modulus, self.bearing.ball_poisson, self.bearing.ball_modulus, self.bearing.ball_poisson)

    def hertz_constants(self) -> tuple[float, float]:
        """(K_i, K_o) [N/m^1.5] of the ball-race contacts (zero contact angle)."""
        D, dm = self.bearing.ball_diameter, self.bearing.pitch_diameter
        es = self.e_star_race
        Ki = laws_contact.hertz_constant(*laws_bearing.race_radii(D, dm, self.bearing.inner_groove_radius, "inner"), es, self.fidelity.hertz)
        Ko = laws_contact.hertz_constant(*laws_bearing.race_radii(D, dm, self.bearing.outer_groove_radius, "outer"), es, self.fidelity.hertz)
        return Ki, Ko

    def race_film_reference_load(self) -> float:
        """Reference load [N] of the race films: Stribeck's most loaded ball c F_r / Z, c = 4.37
        (:data:`lubedyn.lubrication.laws.bearing.STRIBECK`), or the axial share F_a / Z when larger; at least 1 N."""
        return max(laws_bearing.STRIBECK["point"] * self.operating.radial_load / self.bearing.n_balls, self.operating.axial_load / self.bearing.n_balls,
                   1.0)

    def race_film_coefficients(self) -> tuple[float, float]:
        """(c_i, c_o) of the race films h_c = c u_e^0.67 [m with u_e in m/s].

        Hamrock & Dowson (1977) central film of an elliptic contact
        (:func:`lubedyn.lubrication.laws.film.hamrock_dowson_central`),
        U = eta0 u_e / (E' R_x), G = alpha E', W = Q / (E' R_x^2), E' = 2 E*,
        k = a/b from the exact ellipse (m = 1 - (b/a)^2 of
        :func:`lubedyn.lubrication.laws.contact.ellipticity_parameter`), evaluated at
        :meth:`race_film_reference_load` (the film depends on the load only as
        Q^-0.067: a tenfold load changes it by 14 %).  Isothermal, fully
        flooded, smooth surfaces; the film adds h_c to the solids' approach."""
        D, dm = self.bearing.ball_diameter, self.bearing.pitch_diameter
        e_prime = 2.0 * self.e_star_race
        q = self.race_film_reference_load()
        out = []
        for race, groove in (("inner", self.bearing.inner_groove_radius), ("outer", self.bearing.outer_groove_radius)):
            rx, ry = laws_bearing.race_radii(D, dm, groove, race)
            k = 1.0 / math.sqrt(1.0 - laws_contact.ellipticity_parameter(ry / rx))
            U1 = self.films.viscosity / (e_prime * rx)  # U per (m/s)
            G = self.films.pressure_viscosity * e_prime
            W = q / (e_prime * rx * rx)
            out.append(hamrock_dowson_central(U1, G, W, k) * rx)
        return out[0], out[1]

    def race_film_thickness(self, entrainment_speed: float) -> tuple[float, float]:
        """(h_ci, h_co) [m] of the closed-form race films at an entrainment speed [m/s]."""
        ci, co = self.race_film_coefficients()
        return ci * entrainment_speed**0.67, co * entrainment_speed**0.67

    @property
    def contact_angle_free(self) -> float:
        """Free contact angle [rad] from the clearance: cos b0 = 1 - P_d/(2 B D) (0 for P_d <= 0)."""
        return laws_bearing.free_contact_angle(self.bearing.ball_diameter, self.bearing.inner_groove_radius, self.bearing.outer_groove_radius,
                                               self.bearing.diametral_clearance)

    @property
    def omega_inner(self) -> float:
        return self.operating.speed

    @property
    def n_per_ball(self) -> int:
        return NB_6DOF if self.fidelity.dof == "6dof" else NB_PLANAR

    @property
    def n_states(self) -> int:
        return N_RING + self.bearing.n_balls + self.bearing.n_balls * self.n_per_ball

    def ball_offset(self, j: int) -> int:
        """Index of ball j's first state entry."""
        return N_RING + self.bearing.n_balls + j * self.n_per_ball

    def cage_speed(self, contact_angle: float = 0.0) -> float:
        """Epicyclic ball-train speed omega_i (1 - D cos a/d_m)/2 [rad/s]."""
        return laws_bearing.cage_speed(self.bearing.ball_diameter, self.bearing.pitch_diameter, contact_angle, self.omega_inner)

    # numba arguments ----------------------------------------------------------
    def args(self) -> tuple:
        """The numba tuple ``(iopt, P, bbp, slots, map_ax0, map_ax1, map_ax2, map_vals, map_opts, counter, tmap)``
        (the five film-map entries None without a film map, ``tmap`` None without traction maps).

        Built once per model and cached: ``counter`` (int64[1]) counts film-map
        queries outside the map's axes over every run with these args
        (:attr:`map_counter`)."""
        cached = self.__dict__.get("_args_cache")
        if cached is not None:
            return cached
        out = self._build_args()
        object.__setattr__(self, "_args_cache", out)
        return out

    @property
    def map_counter(self) -> np.ndarray:
        """int64[1]: film- and traction-map queries outside the axes (clamped) so far."""
        return self.args().counter

    def _build_args(self) -> KernelArgs:
        D, dm = self.bearing.ball_diameter, self.bearing.pitch_diameter
        Rb = 0.5 * D
        v = dict.fromkeys(PARAMETER_DTYPE.names, 0.0)   # the fields of options not in use stay 0
        v["z"] = self.bearing.n_balls
        v["dof"] = DOFS[self.fidelity.dof]
        v["film"] = FILM_KINDS[self.films.ball_ball]
        v["drive"] = SCENARIOS[self.operating.scenario]
        v["traction"] = TRACTIONS[self.fidelity.traction]
        v["ballball"] = int(bool(self.fidelity.ball_ball))
        Ki, Ko = self.hertz_constants()
        Pd4 = 0.25 * self.bearing.diametral_clearance
        v["d"], v["rb"] = D, Rb
        v["ro"], v["ri"] = self.bearing.outer_groove_radius, self.bearing.inner_groove_radius
        v["roc"] = 0.5 * dm + Rb + Pd4 - self.bearing.outer_groove_radius
        v["ric"] = 0.5 * dm - Rb - Pd4 + self.bearing.inner_groove_radius
        v["mb"], v["jb"] = self.mass, self.ball_inertia
        v["mr"], v["jr"] = self.bearing.ring_mass, self.bearing.ring_inertia
        v["jrot"] = self.bearing.rotor_inertia if math.isfinite(self.bearing.rotor_inertia) else 0.0
        v["ki"], v["ko"] = Ki, Ko
        if self.films.race == "closed_form":
            v["hci"], v["hco"] = self.race_film_coefficients()
        v["alpha"] = self.fidelity.race_damping
        v["mu"], v["srr"], v["vreg"] = self.fidelity.traction_limit, self.fidelity.traction_srr, self.fidelity.traction_slip_regularisation
        v["g"] = self.operating.gravity
        v["fx"] = 0.0
        v["fy"] = -(self.operating.radial_load - self.bearing.ring_mass * self.operating.gravity)
        v["fz"] = self.operating.axial_load
        v["murot"], v["rc"], v["wreg"] = self.operating.rotor_friction, self.operating.rotor_contact_radius, self.operating.rotor_slip_regularisation
        v["nrot"] = self.operating.radial_load
        v["sw"], v["sl"], v["sblend"] = self.slots.width, self.slots.length, self.slots.blend
        # slot edges: sphere against an edge rounded with r_e along a circle of radius R_e
        hw = 0.5 * self.slots.width
        v["reo"] = v["roc"] + math.sqrt(self.bearing.outer_groove_radius**2 - hw * hw)
        v["rei"] = v["ric"] - math.sqrt(self.bearing.inner_groove_radius**2 - hw * hw)
        es = self.e_star_race
        re = self.slots.edge_radius
        rxo, ryo = laws_contact.relative_radii([2.0 / D, -1.0 / v["reo"]], [2.0 / D, 1.0 / re])
        rxi, ryi = laws_contact.relative_radii([2.0 / D, 1.0 / v["rei"]], [2.0 / D, 1.0 / re])
        v["keo"] = laws_contact.hertz_constant(max(rxo, ryo), min(rxo, ryo), es, self.fidelity.hertz)
        v["kei"] = laws_contact.hertz_constant(max(rxi, ryi), min(rxi, ryi), es, self.fidelity.hertz)
        v["qstab"] = self.fidelity.quaternion_stabilisation
        bbp = ball_ball_parameters(
            ball_radius=Rb, e_star=self.e_star_ball, yield_stress=self.fidelity.yield_stress,
            damping_alpha=self.fidelity.ball_ball_damping, viscosity=self.films.viscosity if self.films.ball_ball != "none" else 0.0,
            rupture_thickness=self.films.rupture_thickness, cutoff_gap=self.films.cutoff_gap,
            mu_film=self.films.friction_film, mu_boundary=self.films.friction_boundary,
            slip_regularisation=self.films.slip_regularisation, memory_time=self.fidelity.plastic_memory_time,
            pressure_viscosity=self.films.pressure_viscosity, friction_law=self.films.friction_law,
            asperity_slope=self.films.asperity_slope, entrapped_damping=self.films.entrapped_damping)
        slots = np.zeros((len(self.slots.azimuths), 2))
        for k, az in enumerate(self.slots.azimuths):
            slots[k, 0] = az
            slots[k, 1] = RACES[self.slots.race]
        # a model without a film map or traction maps passes None in their places: numba then prunes the
        # map readers by type and never compiles them (the args' types select the compiled variant)
        film_map = None
        if self.films.ball_ball == "map":
            film_map = _map_arrays(self.films.map, self.films.map_speed_axis)
            bbp = with_map_ends(bbp, film_map.ax0, film_map.ax1, film_map.opts)
        counter = np.zeros(1, dtype=np.int64)
        tmap = _traction_arrays(self.fidelity.traction_maps) if self.fidelity.traction == "map" else None
        return KernelArgs(parameter_record(v), ball_ball_row(bbp), slots, film_map, counter, tmap)

    # state layout ---------------------------------------------------------------
    def state_layout(self) -> list[tuple[str, str]]:
        """(name, unit) of every state entry, in order."""
        out = [("Inner ring x", "m"), ("Inner ring y", "m"), ("Inner ring z", "m"), ("Inner ring angle", "rad"),
               ("Inner ring vx", "m/s"), ("Inner ring vy", "m/s"), ("Inner ring vz", "m/s"),
               ("Inner ring speed", "rad/s"), ("Rotor speed", "rad/s")]
        out += [(f"Pair {j}-{(j + 1) % self.bearing.n_balls} plastic memory", "m") for j in range(self.bearing.n_balls)]
        for j in range(self.bearing.n_balls):
            if self.fidelity.dof == "6dof":
                names = [("x", "m"), ("y", "m"), ("z", "m"), ("q0", "-"), ("q1", "-"), ("q2", "-"), ("q3", "-"),
                         ("vx", "m/s"), ("vy", "m/s"), ("vz", "m/s"), ("body wx", "rad/s"), ("body wy", "rad/s"),
                         ("body wz", "rad/s")]
            else:
                names = [("orbital angle", "rad"), ("radial position", "m"), ("spin angle", "rad"),
                         ("orbital speed", "rad/s"), ("radial speed", "m/s"), ("spin speed", "rad/s")]
            out += [(f"Ball {j} {n}", u) for n, u in names]
        return out

    def state_scales(self) -> np.ndarray:
        """A natural perturbation scale of every state entry (for tangent
        dynamics): 1 um for lengths, the speed a 1 um oscillation at the
        contact frequency has for velocities, 1e-4 for quaternion entries and
        angles, 1 rad/s for angular speeds."""
        k = 1.5 * max(self.hertz_constants()) ** (2.0 / 3.0) * max(self.operating.radial_load, 100.0) ** (1.0 / 3.0)
        omega = math.sqrt(k / self.mass)
        unit = {"m": 1e-6, "m/s": 1e-6 * omega, "rad": 1e-4, "-": 1e-4, "rad/s": 1.0}
        return np.array([unit[u] for _, u in self.state_layout()])

    def state_names(self) -> list[str]:
        """Names with units, e.g. ``"Ball 0 x [m]"``."""
        return [f"{n} [{u}]" for n, u in self.state_layout()]

    # initial state ---------------------------------------------------------------
    def _pack(self, ring, psi, r, z, psidot, spin):
        """State vector from ring entries and per-ball orbital data."""
        y = np.zeros(self.n_states)
        y[:N_RING] = ring
        for j in range(self.bearing.n_balls):
            b = self.ball_offset(j)
            if self.fidelity.dof == "6dof":
                c, s = math.cos(psi[j]), math.sin(psi[j])
                y[b:b + 3] = r[j] * c, r[j] * s, z[j]
                y[b + 3] = 1.0
                y[b + 7:b + 9] = -r[j] * psidot[j] * s, r[j] * psidot[j] * c
                y[b + 12] = spin[j]
            else:
                y[b], y[b + 1], y[b + 3], y[b + 5] = psi[j], r[j], psidot[j], spin[j]
        return y

    def initial_state(self, ball_azimuths=None, settle=True) -> np.ndarray:
        """Quasi-static initial state.

        Balls at ``ball_azimuths`` [rad] (default: the ``initial`` group's arrangement, evenly spaced
        from ``initial.first_ball_azimuth`` unless it says otherwise), each in radial (and axial) equilibrium
        between the races, the inner ring in force equilibrium under F_r,
        F_a and gravity (scipy ``root`` on the same force kernel, centrifugal
        forces included for the ``"steady"`` scenario, where the balls orbit at
        the epicyclic speed and roll without slip about the axis-parallel
        direction).  ``"drop"``/``"free"``: everything at rest, the rotor at
        ``operating.speed``; the ring gets the downward ``drop_speed``, and the ``initial`` group's
        random kick (if any) in the x-y plane.
        ``settle=False`` returns the unloaded geometric guess.

        Raises DynamicsInputError when no equilibrium exists (a load the
        grooves cannot carry)."""
        Z = self.bearing.n_balls
        D, dm = self.bearing.ball_diameter, self.bearing.pitch_diameter
        kick = (0.0, 0.0)
        if ball_azimuths is None:
            psi, kick = self.initial.ball_azimuths(Z)
            key = ("initial.azimuths" if self.initial.azimuths else
                   "initial.jitter" if self.initial.jitter > 0.0 else "bearing.n_balls")
        else:
            psi = np.asarray(ball_azimuths, dtype=float)
            key = "ball_azimuths"
            if psi.shape != (Z,):
                raise DynamicsInputError(f"ball_azimuths has shape {psi.shape}; it must be ({Z},)", key=key)
        self._check_arrangement(psi, key)
        steady = self.operating.scenario == "steady"
        wc = self.cage_speed(self.contact_angle_free) if steady else 0.0
        spin = np.full(Z, -wc * dm / D)
        psidot = np.full(Z, wc)
        ring = np.zeros(N_RING)
        ring[7] = self.omega_inner if steady else 0.0
        ring[8] = 0.0 if steady else self.omega_inner
        r0 = np.full(Z, 0.5 * dm)
        z0 = np.zeros(Z)
        y0 = self._pack(ring, psi, r0, z0, psidot, spin)
        if not settle:
            return y0
        args = self.args()
        y, err = self._static_solve(args, psi, psidot, spin, ring, wc)
        logger.debug("quasi-static solve: residual %.3g of the mean ball load", err)
        if not (err <= 1e-3):
            raise DynamicsInputError(
                f"operating.radial_load = {self.operating.radial_load:g} N, operating.axial_load = "
                f"{self.operating.axial_load:g} N: no quasi-static equilibrium found (force residual {err:.3g} of the mean ball load); the grooves cannot carry "
                "this load", key="operating.radial_load")
        if self.operating.scenario == "drop":
            y[5] = -self.operating.drop_speed
        y[4] += kick[0]
        y[5] += kick[1]
        diag, _, _ = forces(0.0, y, args)
        amax = float(np.max(np.abs(diag[:, [D_AI, D_AO]])))
        if amax > math.radians(self.fidelity.shoulder_contact_angle_deg):
            raise DynamicsInputError(
                f"operating.axial_load = {self.operating.axial_load:g} N (operating.radial_load = "
                f"{self.operating.radial_load:g} N) drives the contact angle to {math.degrees(amax):.1f} deg, beyond the "
                f"groove shoulders (model.shoulder_contact_angle_deg = {self.fidelity.shoulder_contact_angle_deg:g}): "
                "the bearing cannot carry it", key="operating.axial_load")
        return y

    def _check_arrangement(self, psi, key):
        """Balls in ring order (ball j+1 follows ball j counter-clockwise, less than a turn) and apart: the
        chord between neighbours' centres on the pitch circle must exceed D."""
        Z = self.n_balls
        rel = np.mod(psi - psi[0], 2.0 * np.pi)
        gaps = np.diff(np.append(rel, 2.0 * np.pi))
        if np.any(gaps <= 0.0):
            raise DynamicsInputError(f"{key}: the balls must be in ring order (ball j + 1 counter-clockwise of "
                                     "ball j, within one turn)", key=key)
        chord = self.bearing.pitch_diameter * np.sin(0.5 * gaps)
        j = int(np.argmin(chord))
        if chord[j] <= self.bearing.ball_diameter:
            raise DynamicsInputError(
                f"{key}: balls {j} and {(j + 1) % Z} overlap (centres {chord[j]:.6g} m apart on the pitch circle, "
                f"<= D = {self.bearing.ball_diameter:g} m)", key=key)

    def _ball_seat(self, args, y, j, psi_j, wc, call, dydt):
        """Radial (and axial) equilibrium of ball j for the ring in ``y``; writes y.  ``call``: the rhs's
        compiled entry point for these arguments (:func:`lubedyn.dynamics.specialise.entry_point`, taken once
        per static solve: typing the arguments was 0.65 of the 0.78 s a warm seating took when it was taken
        per ball), ``dydt``: its output buffer."""
        from scipy.optimize import brentq, root

        D, dm = self.bearing.ball_diameter, self.bearing.pitch_diameter
        P = args.P[0]
        m = self.mass
        b = self.ball_offset(j)
        six = self.fidelity.dof == "6dof"
        c, s = math.cos(psi_j), math.sin(psi_j)

        def set_pos(rho, z):
            if six:
                y[b:b + 3] = rho * c, rho * s, z
                y[b + 7:b + 9] = -rho * wc * s, rho * wc * c
            else:
                y[b + 1] = rho

        def res(rho, z):
            set_pos(rho, z)
            call(0.0, y, args, dydt)
            if six:
                return (m * (dydt[b + 7] * c + dydt[b + 8] * s + wc * wc * rho), m * dydt[b + 9])
            return (m * dydt[b + 4], 0.0)

        # groove centres in the ball's radial plane (rho, z)
        gi = np.array([P.ric + y[0] * c + y[1] * s, y[2]])
        go = np.array([P.roc, 0.0])
        Ki, Ko = P.ki, P.ko
        si, so_ = P.ri - 0.5 * D, P.ro - 0.5 * D
        u = go - gi
        L = float(np.hypot(*u))
        dtot = L - si - so_
        body = np.array([m * wc * wc * 0.5 * dm - m * self.operating.gravity * s, 0.0])
        if dtot > 0.0:
            di = dtot / (1.0 + (Ki / Ko) ** (2.0 / 3.0))
            guess = gi + (si + di) * u / L
        elif np.hypot(*body) > 0.0:
            bh = body / np.hypot(*body)
            if body[0] > 0.0:
                guess = go + (so_ + (np.hypot(*body) / Ko) ** (2.0 / 3.0)) * bh
            else:
                guess = gi + (si + (np.hypot(*body) / Ki) ** (2.0 / 3.0)) * bh
        else:  # loose ball, no body force: anywhere in the clearance; take the middle
            guess = gi + (si - 0.5 * dtot) * u / L
        if not six:
            r0 = float(guess[0])
            f0 = res(r0, 0.0)[0]
            if f0 == 0.0:
                return 0.0
            step = 1e-7
            sign = 1.0 if f0 > 0.0 else -1.0
            r1 = r0
            for _ in range(60):
                r1 = r1 + sign * step
                if res(r1, 0.0)[0] * f0 <= 0.0:
                    break
                step *= 2.0
            lo, hi = min(r0, r1), max(r0, r1)
            rr = brentq(lambda r: res(r, 0.0)[0], lo, hi, xtol=1e-16, rtol=1e-15)
            return abs(res(rr, 0.0)[0])
        sc = 1e-6
        # maxfev: the bundled cases' seats take at most 51 evaluations (3-25 krpm); a seat that takes 200
        # has no equilibrium at this ring position (the residual reports it), and hybr's default, 600,
        # tripled the time to refuse a bearing that cannot carry its load
        sol = root(lambda x: np.array(res(guess[0] + sc * x[0], guess[1] + sc * x[1])), np.zeros(2),
                   method="hybr", options=dict(xtol=1e-13, maxfev=200))
        f = res(guess[0] + sc * sol.x[0], guess[1] + sc * sol.x[1])
        return float(np.hypot(*f))

    def _static_solve(self, args, psi, psidot, spin, ring, wc):
        """Ring force balance (hybr) around per-ball equilibria; returns (y, residual)."""
        from scipy.optimize import root

        Z = self.bearing.n_balls
        six = self.fidelity.dof == "6dof"
        nr = 3 if six else 2
        y = self._pack(ring, psi, np.full(Z, 0.5 * self.bearing.pitch_diameter), np.zeros(Z), psidot, spin)
        Ki, Ko = self.hertz_constants()
        Kn = laws_contact.series_constant(Ki, Ko)
        fscale = max(self.operating.radial_load, self.operating.axial_load, 1.0) / Z
        scale = (max(self.operating.radial_load, self.operating.axial_load, 1.0) / (Z * Kn)) ** (2.0 / 3.0)
        dydt, seat = np.empty_like(y), np.empty_like(y)
        call = entry_point(rhs, 0.0, y, args, dydt)  # no typing per call (lubedyn.dynamics.specialise.entry_point)
        worst = [0.0]

        def residual(x):
            y[:nr] = x * scale
            worst[0] = 0.0
            for j in range(Z):
                worst[0] = max(worst[0], self._ball_seat(args, y, j, psi[j], wc, call, seat))
            call(0.0, y, args, dydt)
            return dydt[4:4 + nr] * self.bearing.ring_mass / fscale

        x0 = np.zeros(nr)
        x0[1] = -(5.0 * self.operating.radial_load / Z / Kn) ** (2.0 / 3.0) / scale
        if six and self.operating.axial_load > 0.0:
            BD = self.bearing.inner_groove_radius + self.bearing.outer_groove_radius - self.bearing.ball_diameter
            x0[2] = math.sqrt(2.0 * BD * (self.operating.axial_load / (Z * Kn)) ** (2.0 / 3.0)) * 1.2 / scale
        sol = root(residual, x0, method="hybr", options=dict(xtol=1e-12))
        r = residual(sol.x)
        err = max(float(np.max(np.abs(r))), worst[0] / fscale)
        return y, err

    def omega_max(self, y=None) -> float:
        """Estimate of the highest rate [rad/s] of the linearised bearing at a state
        (for the explicit step limit): the ball between its two stiffest loaded
        contacts, sqrt(2 k/m) with k = 1.5 Q/delta = 1.5 K^(2/3) Q^(1/3), or the
        contact damping rate 2 alpha Q/m, whichever is larger."""
        if y is None:
            y = self.initial_state()
        diag, _, _ = forces(0.0, np.asarray(y, dtype=float), self.args())
        Ki, Ko = self.hertz_constants()
        Q = max(float(np.max(diag[:, D_QI])), float(np.max(diag[:, D_QO])), 1.0)
        k = 1.5 * max(Ki, Ko) ** (2.0 / 3.0) * Q ** (1.0 / 3.0)
        # Hunt-Crossley damping c = alpha Q on both contacts: a real eigenvalue -c/m (RK4 limit 2.79 on
        # the real axis, close to 2.83 on the imaginary one)
        rate = self.fidelity.race_damping * 2.0 * Q / self.mass
        return max(math.sqrt(2.0 * k / self.mass), rate)


    def replace(self, **changes) -> "CagelessBearing":
        """A copy with some values changed, checked again.  ``changes`` by group (``operating={"speed": 1e3}``,
        or a whole group) or by case key (``**{"model.dof": "planar"}``); ``model`` and ``fidelity`` name the
        same group."""
        groups = {}
        for name, value in changes.items():
            table, _, field_name = name.partition(".")
            attr = self.GROUPS.get(table, table if table in self.GROUP_CLASSES else None)
            if attr is None:
                raise DynamicsInputError(f"{name} is not a group of the bearing model; choose one of "
                                         f"{', '.join(self.GROUPS)}{did_you_mean(table, self.GROUPS, n=2)}", key=name)
            if field_name:
                groups.setdefault(attr, {})[field_name] = value
            elif isinstance(value, dict):
                groups.setdefault(attr, {}).update(value)
            else:
                groups[attr] = value
        kw = {f.name: getattr(self, f.name) for f in fields(self)}
        for attr, value in groups.items():
            kw[attr] = kw[attr].updated(value)
        return CagelessBearing(**kw)
