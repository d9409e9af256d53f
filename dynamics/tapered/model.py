"""The tapered roller bearing as a compiled right-hand side: parameters, the start state from the
quasi-static equilibrium, the state's names and the diagnostics of a trajectory.

:class:`TaperedBearing` holds the geometry (:class:`lubedyn.lubrication.laws.tapered.TaperedRollerGeometry`) and
the frozen groups of :mod:`lubedyn.dynamics.tapered.groups`; it packs them into the arrays of
:func:`lubedyn.dynamics.tapered.kernels.rhs` (``args()``), places the cone and the rollers where
:func:`lubedyn.dynamics.tapered.quasistatic.solve` finds them in equilibrium, the rollers orbiting at the ideal
cage speed and spinning at their ideal speed, the cage concentric at the ideal cage speed
(``start_state``), so a run does not begin with an impact, and reads a trajectory back
(:meth:`TaperedBearing.diagnostics`: loads per slice and contact, tilt, skew, slip, speeds).
"""
from __future__ import annotations

import logging
import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from lubedyn.lubrication.laws import flange as laws_flange
from lubedyn.lubrication.laws import slices as sl
from lubedyn.lubrication.laws.cage import POCKET_SWITCHES
from lubedyn.lubrication.laws.tapered import TaperedRollerGeometry

from ..errors import DynamicsInputError
from ..groups import fail
from ..rotations import quat_rotate_inverse
from . import kernels as K
from . import layout as L
from .groups import Cage, Fidelity, Flange, Initial, Lubricant, Operating
from .quasistatic import QuasiStaticResult, solve
from ..integrators import spectral_step, stability_limit
from ..interp import hermite_data, hermite_value, locate_call, prepare_axis
from lubedyn.lubrication.laws.film import dowson_toyoda_central

log = logging.getLogger(__name__)


def _race_index(race: str) -> int:
    """0 for "cup", 1 for "cone" (the kernel's raceway index); anything else is an input error."""
    if race not in ("cup", "cone"):
        raise DynamicsInputError(f"race = {race!r} is not a raceway; choose 'cup' or 'cone'")
    return 0 if race == "cup" else 1


def sliding_decay_rate(k1: float, k2: float, m: float, ix: float, rho: float) -> float:
    """Larger decay rate [1/s] of a roller's rolling-direction speed and spin under linear tractions of
    slopes ``k1`` (cup) and ``k2`` (cone) [N s/m] at radius ``rho`` [m] on opposite sides (mass ``m``,
    axial moment of inertia ``ix``): the larger eigenvalue of [[(k1 + k2)/m, (k1 - k2) rho/m], [(k1 - k2)
    rho/ix, (k1 + k2) rho^2/ix]] (:meth:`TaperedBearing.traction_rate`)."""
    tr = (k1 + k2) * (1.0 / m + rho**2 / ix)
    det = 4.0 * k1 * k2 * rho**2 / (m * ix)
    return 0.5 * (tr + math.sqrt(max(tr * tr - 4.0 * det, 0.0)))


@dataclass(frozen=True, kw_only=True)
class TaperedBearing:
    """Paper A's tapered roller bearing (SI units): the ``geometry`` law and six frozen groups
    (:mod:`lubedyn.dynamics.tapered.groups`): ``operating``, ``fidelity`` (the case's ``[model]``),
    ``lubricant``, ``cage`` (needed with ``fidelity.pocket`` != "none"), ``flange`` (needed with
    ``fidelity.flange_friction`` != "none") and ``initial``.  Paper A's values come from
    :mod:`lubedyn.papers.wu2018.parameters` (``tapered_bearing()``); every error names the case key."""

    geometry: TaperedRollerGeometry
    operating: Operating
    fidelity: Fidelity = Fidelity()
    lubricant: Lubricant
    cage: Cage | None = None
    flange: Flange | None = None
    initial: Initial = Initial()
    #: raceway traction "map": the roller EHL maps (cup, cone), objects with a film map's interface
    #: (:class:`lubedyn.maps.FilmMap`: ``axes``, ``sheared`` and ``map(output, *coords)``), read at the
    #: run's entrainment speed by :meth:`map_traction_tables`
    traction_maps: tuple = ()
    #: ``flange.rib_film = "ehl"``: the rib's EHL film map (kind ``ehl_rib``, axes flange load [N] and
    #: entrainment speed [m/s]; :func:`lubedyn.scenes.tapered.rib_film_map`), read by :meth:`rib_film`
    rib_film_map: object = None

    GROUP_CLASSES: ClassVar[dict] = {"operating": Operating, "fidelity": Fidelity, "lubricant": Lubricant,
                                     "cage": Cage, "flange": Flange, "initial": Initial}

    def __post_init__(self):
        for name, cls in self.GROUP_CLASSES.items():
            group = getattr(self, name)
            if isinstance(group, dict):
                object.__setattr__(self, name, cls.build(group))
            elif group is not None and not isinstance(group, cls):
                raise DynamicsInputError(f"{name} must be a {cls.__name__} (or a dict of its fields), not "
                                         f"{type(group).__name__}", key=cls.TABLE)
        f = self.fidelity
        if f.pocket != "none" and self.cage is None:
            raise fail("cage", None, f"must be given with model.pocket = {f.pocket!r}")
        if f.flange_friction != "none" and self.flange is None:
            raise fail("flange", None, f"must be given with model.flange_friction = {f.flange_friction!r}")
        if self.flange is not None and self.flange.rib_film == "ehl" and self.rib_film_map is None:
            raise fail("flange.rib_film", "ehl", "needs the rib's EHL film map (rib_film_map; the tapered scene loads "
                                                 "the shipped one of the case's grease)")
        if "contact" in (f.pocket, f.guide_land) and self.cage.modulus is None:
            raise fail("cage.modulus", None, "must be given with a contact-only pocket or guide land")
        if f.pocket == "film" or f.guide_land == "film":
            for name in ("pocket_critical_film", "pocket_stiffness", "land_critical_film"):
                if not getattr(self.cage, name) > 0.0:
                    raise fail(f"cage.{name}", getattr(self.cage, name), "must be > 0 with the film pocket or land")
        if f.traction == "map" and len(self.traction_maps) != 2:
            raise fail("model.traction", "map", "needs the roller EHL maps of both raceways (cup, cone)")
        needs_grease = f.traction == "limited" or f.flange_friction != "none"
        if needs_grease and self.lubricant.grease() is None:
            raise fail("lubricant.consistency", None, "must be given (a grease) with model.traction = 'limited' or "
                                                      "a flange friction")

    # ---------------------------------------------------------------- convenience
    @property
    def n_rollers(self) -> int:
        return int(self.geometry.n_rollers)

    @property
    def n_slices(self) -> int:
        return int(self.fidelity.slices)

    @property
    def speed(self) -> float:
        return float(self.operating.speed)

    @property
    def traction(self) -> str:
        return self.fidelity.traction

    @property
    def has_cage(self) -> bool:
        return self.fidelity.pocket != "none"

    @property
    def tilt_free(self) -> bool:
        return self.operating.cone_tilt == "free"

    @property
    def tilt_index(self) -> int:
        """Offset of the cone's tilt block (theta_y, theta_z, rates) in the state: after the last body."""
        return L.N_CONE + L.NB * (self.n_rollers + (1 if self.has_cage else 0))

    @property
    def n_state(self) -> int:
        return self.tilt_index + (L.N_TILT if self.tilt_free else 0)

    def cone_inertia(self) -> tuple[float, float]:
        """(I_x, I_t) [kg m^2] of the cone, assumed (paper A gives no ring data): a steel annulus of the
        cone's mass m (``model.cone_mass``) and width w from the raceway's small end, -l_e cos(beta)/2, to
        the guide land's far edge, outer radius the cone raceway's contact radius r_o, bore r_i from the
        mass, pi (r_o^2 - r_i^2) w rho = m; I_x = m (r_o^2 + r_i^2)/2, I_t = m (3 (r_o^2 + r_i^2) + w^2)/12
        (about the ring's centre, taken at the cone's reference point)."""
        g, m = self.geometry, self.fidelity.cone_mass
        w = g.land_x + 0.5 * g.guide_land_width + 0.5 * g.effective_length * math.cos(g.roller_axis_angle)
        ro = float(g.contact_radii[1])
        ri2 = ro * ro - m / (math.pi * w * g.density)
        if not ri2 > 0.0:
            raise fail("model.cone_mass", m, f"kg exceeds a solid steel disc of the cone's {2e3 * ro:.4g} mm raceway "
                                             f"diameter and {1e3 * w:.4g} mm width (the cone's assumed inertia)")
        return annulus_inertia(m, ro * ro + ri2, w)

    def ideal(self) -> dict:
        """The geometry's ideal kinematics at the cone speed (:meth:`TaperedRollerGeometry.kinematics`)."""
        return self.geometry.kinematics(self.speed)

    def pocket_modulus(self) -> float:
        """E' = 2/((1 - nu_s^2)/E_s + (1 - nu_c^2)/E_c) [Pa] of steel on the cage's polyamide."""
        g, c = self.geometry, self.cage
        return 2.0 / ((1.0 - g.poisson**2) / g.modulus + (1.0 - c.poisson**2) / c.modulus)

    # ---------------------------------------------------------------- packing
    def rib_film(self, qs: QuasiStaticResult | None = None) -> float:
        """The rib's central film [m] (``flange.rib_film``), evaluated once at the start's largest flange
        load and the rib's ideal entrainment speed (floored at 1 mm/s: at rest the film vanishes, the
        asperity share is then 1)."""
        g = self.geometry
        qs = self.quasi_static() if qs is None else qs
        load = max(float(np.max(qs.flange_loads)), 1.0)
        speed = max(self.rib_speeds()[1], 1e-3)
        if self.flange.rib_film == "ehl":
            return self.rib_map_film(load, speed)
        return laws_flange.rib_film(self.flange.rib_film, load, speed, self.lubricant.viscosity(),
                                    self.lubricant.pressure_viscosity, g.e_prime, g.end_sphere_radius,
                                    g.flange_point[1], g.flange_contact_angle)

    def rib_map_film(self, load: float, speed: float) -> float:
        """The central film [m] of :attr:`rib_film_map` at flange ``load`` [N] and entrainment ``speed`` [m/s]
        (``flange.rib_film = "ehl"``); a point outside the map's axes is a one-line error naming the key."""
        fmap = self.rib_film_map
        for axis, value in zip(fmap.axes, (load, speed)):
            lo, hi = float(axis.nodes[0]), float(axis.nodes[-1])
            if not lo <= value <= hi:
                raise fail("flange.rib_film", "ehl", f"reads the rib's EHL film map at {axis.name} = {value:.4g}, "
                                                     f"outside its axis {lo:.4g}-{hi:.4g}")
        return float(fmap("Central film thickness [m]", load, speed))

    def rib_speeds(self) -> tuple[float, float]:
        """(sliding, entrainment) speeds [m/s] of the roller end on the rib at the ideal kinematics, the
        roller in its meridional plane at azimuth 0, both in the cage frame, where the contact point P
        is at rest (it orbits with the roller): rib surface (Omega - omega_c) e_x x P, roller end
        w_s e x (P - c); entrainment the mean of the two (the speed the Reynolds equation of a steady
        contact takes), sliding their difference (the same in every frame).  In the ground frame the
        mean would carry the contact's own orbital speed omega_c r_P as well (measured at 2,800 rpm:
        22.39 m/s against the cage frame's 11.32 m/s; 8.09-20.21 m/s over 2-5 krpm)."""
        g = self.geometry
        kin = self.ideal()
        wc, ws = kin["cage speed [rad/s]"], -kin["roller spin relative to cage [rad/s]"]
        beta = g.roller_axis_angle
        e = np.array([math.cos(beta), math.sin(beta), 0.0])
        mid = np.array([0.0, g.pitch_radius, 0.0])
        sphere = mid + g.sphere_center_u * e
        n = np.array([g.flange_normal[0], g.flange_normal[1], 0.0])
        p = sphere - g.end_sphere_radius * n
        ex = np.array([1.0, 0.0, 0.0])
        rib = np.cross((self.speed - wc) * ex, p)
        roller = np.cross(ws * e, p - mid)
        return float(np.linalg.norm(roller - rib)), float(np.linalg.norm(0.5 * (roller + rib)))

    def args(self, qs: QuasiStaticResult | None = None):
        """The :class:`lubedyn.dynamics.tapered.layout.KernelArgs` of :func:`lubedyn.dynamics.tapered.kernels.rhs`:
        the parameter record (every field of :data:`lubedyn.dynamics.tapered.layout.PARAMETERS` set here;
        those of options not in use stay 0), the slices and the traction tables."""
        g, op, fi, lu = self.geometry, self.operating, self.fidelity, self.lubricant
        u, _ = g.slices(fi.slices)
        rho = np.asarray(g.roller_radius(u), dtype=float)
        m, ix, iy, uc = g.roller_mass_properties()
        v = dict.fromkeys(L.PARAMETER_DTYPE.names, 0.0)
        v["z"], v["ns"] = self.n_rollers, fi.slices
        v["m"], v["ix"], v["iy"], v["uc"] = m, ix, iy, uc
        v["mc"], v["omega"] = fi.cone_mass, op.speed
        v["fa"], v["fr"] = op.axial_load, op.radial_load
        v["axial"] = L.AXIAL_MODES[op.axial]
        v["grav"] = op.gravity
        if self.tilt_free:
            v["tilt"], v["tiltat"] = L.CONE_TILTS["free"], self.tilt_index
            v["iconex"], v["iconet"] = self.cone_inertia()
            v["loadx"] = op.load_offset
            v["my"], v["mz"] = (float(v) for v in op.applied_moment)
            v["landx"] = g.land_x
        v["kw"] = sl.slice_constant(sl.palmgren_line_constant(g.effective_length), fi.slices)
        v["kf"] = g.flange_hertz_constant()
        v["alpha"] = fi.damping_alpha
        v["rs"], v["us"] = g.end_sphere_radius, g.sphere_center_u
        (v["cupx"], v["cupr"]), (v["cupnx"], v["cupnr"]) = g.cup_point, g.cup_normal
        (v["conx"], v["conr"]), (v["connx"], v["connr"]) = g.cone_point, g.cone_normal
        (v["flx"], v["flr"]), (v["flnx"], v["flnr"]) = g.flange_point, g.flange_normal
        v["contacts"] = 1.0 if fi.contacts else 0.0
        v["qstab"] = fi.quaternion_stabilisation
        v["traction"] = L.TRACTIONS[fi.traction]
        v["eta"], v["pvc"], v["ep"] = lu.viscosity(), lu.pressure_viscosity, g.e_prime
        v["etao"], v["etai"] = lu.film_viscosities()
        v["rxo"], v["rxi"] = g.reduced_radius("cup"), g.reduced_radius("cone")
        v["ue"] = self.entrainment_speed
        v["width"] = g.effective_length / fi.slices
        v["vreg"] = fi.friction_speed
        grease = lu.grease()
        if grease is not None:
            v["tauy"], v["phi0"], v["nexp"] = grease.yield_stress, grease.consistency, grease.exponent
            v["alphag"], v["taul0"] = grease.pressure_viscosity, lu.limiting_stress
            v["gammal"], v["dr"] = lu.limiting_slope, lu.yield_rate
        v["gshear"] = lu.shear_modulus
        if fi.flange_friction != "none":
            fl = self.flange
            v["ffric"] = L.FLANGE_FRICTIONS[fi.flange_friction]
            v["mua"], v["fbc"], v["fcc"] = fl.asperity_friction, fl.asperity_b, fl.asperity_c
            v["hrib"] = self.rib_film(qs)
            v["lam"] = v["hrib"] / fl.roughness
            unit = laws_flange.rib_hertz(1.0, g.end_sphere_radius, g.flange_point[1], g.flange_contact_angle,
                                         g.e_star)
            v["fa1"], v["fb1"], v["fp01"] = unit.a, unit.b, unit.p0
        if self.has_cage:
            c = self.cage
            ro, ri, h = 0.5 * g.cage_outer_diameter, 0.5 * g.cage_inner_diameter, g.cage_thickness
            v["cage"], v["mcg"] = 1.0, c.mass
            # the cage ring as an annulus (its bars' share of the inertia is not known: assumed)
            v["icx"], v["ict"] = annulus_inertia(c.mass, ro * ro + ri * ri, h)
            v["pocket"], v["len"], v["rhom"] = g.pocket_clearance, g.effective_length, g.mean_roller_radius
            v["hcrit"], v["kh"], v["ch"] = c.pocket_critical_film, c.pocket_stiffness, c.pocket_damping
            v["mubd"], v["switch"] = c.boundary_friction, POCKET_SWITCHES[fi.pocket_switch]
            v["rland"], v["cland"] = g.land_radius, 0.5 * g.guide_land_clearance
            v["bland"], v["hland"] = g.guide_land_width, c.land_critical_film
            v["pocketmode"], v["landmode"] = L.POCKETS[fi.pocket], L.LANDS[fi.guide_land]
            if fi.side_beams:
                if not (c.side_beam_clearance > 0.0 and c.side_beam_thickness > 0.0):
                    raise fail("cage.side_beam_clearance", c.side_beam_clearance,
                               "and cage.side_beam_thickness must be > 0 with model.side_beams = true")
                v["sidegap"], v["hside"] = c.side_beam_clearance, c.side_beam_thickness
                v["pitch"], v["pockx"], v["beta0"] = g.pitch_radius, -g.cage_x, g.roller_axis_angle
                v["dlarge"], v["dsmall"] = g.large_end_diameter, g.small_end_diameter
            if c.modulus is not None:
                ep = self.pocket_modulus()
                v["kpocket"] = sl.line_constant(g.effective_length, ep)
                v["kland"] = sl.line_constant(g.guide_land_width, ep)
        P = L.parameter_record(v)
        table, maps = L.no_traction_table(), L.no_map_table()
        if fi.traction == "limited" and fi.traction_evaluation == "table":
            table = self.traction_tables(P[0])
        if fi.traction == "map":
            maps = self.map_traction_tables(P[0])
        return L.KernelArgs(P, np.ascontiguousarray(u), np.ascontiguousarray(rho), table, maps)

    #: traction tables: nodes along the sliding speed (log, 1e-12-100 m/s) and the line load (log, 8
    #: decades below the load of :data:`TABLE_PEAK_PRESSURE`)
    TABLE_NODES: ClassVar[tuple[int, int]] = (128, 256)
    TABLE_SPEEDS: ClassVar[tuple[float, float]] = (1e-12, 100.0)
    TABLE_PEAK_PRESSURE: ClassVar[float] = 4e9
    TABLE_LOAD_DECADES: ClassVar[float] = 8.0

    def traction_tables(self, P: np.record) -> "L.TractionTable":
        """The limited traction's tables (``model.traction_evaluation = "table"``) for the parameter record
        ``P``, whose flag ``P.ttab`` it sets.

        Per raceway, :func:`lubedyn.dynamics.tapered.kernels.strip_viscous_traction` (the limited
        Herschel-Bulkley strip law over the slice's Hertz strip, before the elastic shear) on a grid of
        :data:`TABLE_NODES` nodes, log-spaced in the sliding speed over :data:`TABLE_SPEEDS` and in the
        line load over :data:`TABLE_LOAD_DECADES` decades up to the load whose Hertz peak pressure is
        :data:`TABLE_PEAK_PRESSURE` (w = 2 pi R' p0^2/E'), in log-log space with PCHIP node derivatives
        (:func:`lubedyn.dynamics.interp.hermite_data`).  The kernel reads them with
        :func:`lubedyn.dynamics.interp.hermite2` and evaluates the law itself outside them.  The law's film, Hertz
        strip and rheology are fixed for a run, so the traction per length depends on (v_s, w) only.
        Accuracy: tests/test_trb_dynamics.py measures it against the law at random points (the
        traction with its elastic shear within the strip quadrature's own error, 3e-4)."""
        n0, n1 = self.TABLE_NODES
        V = np.logspace(math.log10(self.TABLE_SPEEDS[0]), math.log10(self.TABLE_SPEEDS[1]), n0)
        blocks = []
        for race, radius in enumerate((P.rxo, P.rxi)):
            w_max = 2.0 * math.pi * radius * self.TABLE_PEAK_PRESSURE**2 / P.ep
            W = np.logspace(math.log10(w_max) - self.TABLE_LOAD_DECADES, math.log10(w_max), n1)
            values = K.strip_viscous_table(V, W, race, P)
            if not np.all(values > 0.0):
                raise DynamicsInputError(f"the limited traction is not > 0 on its table ({('cup', 'cone')[race]}): "
                                         "use model.traction_evaluation = 'quadrature'")
            axes = [prepare_axis(V, True), prepare_axis(W, True)]
            blocks.append((axes[0], axes[1], hermite_data(axes, np.log(values))))
        P.ttab = 1.0
        return L.TractionTable(*(np.ascontiguousarray(np.stack(parts), dtype=np.float64) for parts in zip(*blocks)))

    MAP_TRACTION: ClassVar[str] = "Traction coefficient [-]"
    MAP_AXES: ClassVar[list] = ["Line load [N/m]", "Entrainment speed [m/s]", "Slide-to-roll ratio [-]"]

    def map_traction_tables(self, P: np.record) -> "L.MapTable":
        """The roller EHL maps' traction at the run's ideal entrainment speed u_e (raceway traction "map",
        read by :func:`lubedyn.dynamics.tapered.kernels.map_traction_coefficient`); sets the normalised slip
        and the slide-to-roll axis' ends (``P.tma``, ``P.tmb``, ``P.tmcen``, ``P.tmslo``, ``P.tmshi``) of the
        parameter record ``P``.

        Per raceway (cup, cone: :attr:`traction_maps`) the map's sheared traction (lubedyn.maps.FilmMap,
        "sheared": the transition slip s_t(w, u) and the traction G(w, u, x) at the normalised slip's
        coordinate x, cubic Hermite in log w, log u, log x of the log values) restricted to u = u_e: the
        map's own node data (values and derivatives at its w and x nodes) combined with the cubic Hermite
        weights of u_e in its speed cell.  A tricubic Hermite restricted to a plane of one axis is the
        bicubic Hermite of those data, so the kernel reads the map's own interpolant, to round-off
        (tests/test_trb_traction_map.py), at the cost of a 2-D instead of a 3-D query.  The map's traction
        is the film's (a Maxwell fluid capped by limiting shear, in the map's own lubricant:
        lubedyn.film_points.ehl, ``evaluate_ehl_line``), so the kernel adds no elastic shear of its own.
        u_e outside the maps' speed axis is refused (one line naming operating.speed)."""
        ue = float(P.ue)
        spec, shape = None, None
        blocks = []
        for race, fmap in zip(("cup", "cone"), self.traction_maps):
            names = [a.name for a in fmap.axes]
            if names != self.MAP_AXES:
                raise fail("model.traction", "map", f"needs a roller map on {self.MAP_AXES}; the {race} map has {names}")
            sp = fmap.sheared.get(self.MAP_TRACTION)
            if sp is None or getattr(fmap, "method", "hermite") != "hermite":
                raise fail("model.traction", "map", f"needs the {race} map's sheared {self.MAP_TRACTION!r}, "
                                                    "interpolated by cubic Hermite")
            u_axis, s_axis = fmap.axes[1], fmap.axes[2]
            if not u_axis.lo <= ue <= u_axis.hi:
                raise fail("operating.speed", f"{self.speed * 30.0 / math.pi:.6g} rpm",
                           f"gives the entrainment speed {ue:.4g} m/s, outside the {race} roller map's "
                           f"{u_axis.lo:g}-{u_axis.hi:g} m/s (model.traction = 'map'; rebuild the map or use "
                           f"'limited')")
            shift, values = fmap.kernel_arrays(sp["shift"]), fmap.kernel_arrays(sp["values"])
            for ka in (shift, values):
                if tuple(ka.logs) != (1, 1, 1) or ka.logv != 1:
                    raise fail("model.traction", "map", f"needs the {race} map's traction on log axes, log values")
            # u_e's cell and cubic Hermite weights (value, derivative data of the two nodes) in t = log u
            au = shift.axes[1]
            j, t, _ = locate_call(au, math.log(ue))
            wu = hermite_value(au, j, t)

            def restrict(deriv, bits):
                """Node data of the plane u = u_e: index s = s0 + 2 s1 + 4 s2 (bit k: d/d axis k); keep the
                derivative sets ``bits`` of the remaining axes, combine the u-value and u-derivative sets."""
                out = []
                for s0 in bits:
                    out.append(wu[0] * deriv[s0, :, j] + wu[1] * deriv[s0, :, j + 1]
                               + wu[2] * deriv[s0 + 2, :, j] + wu[3] * deriv[s0 + 2, :, j + 1])
                return np.stack(out)

            st = restrict(shift.values, (0, 1))[:, :, 0]          # s_t does not vary along x: its data at x_0
            G = restrict(values.values, (0, 1, 4, 5))             # sets (value, d/dw, d/dx, d2/dw dx)
            aw, ax = shift.axes[0], shift.axes[2]
            key = (float(sp["a"]), float(sp["b"]), float(sp["centre"]), s_axis.lo, s_axis.hi)
            if spec is not None and (key != spec or (aw.size, ax.size) != shape):
                raise fail("model.traction", "map", "needs the cup and cone maps on the same nodes, slide-to-roll "
                                                    "axis and normalised slip")
            spec, shape = key, (aw.size, ax.size)
            blocks.append((aw, ax, st, G))
        P.tma, P.tmb, P.tmcen, P.tmslo, P.tmshi = spec
        return L.MapTable(*(np.ascontiguousarray(np.stack(parts), dtype=np.float64) for parts in zip(*blocks)))

    # ---------------------------------------------------------------- start
    def quasi_static(self) -> QuasiStaticResult:
        """The equilibrium the run starts from (same loads, slices and speed)."""
        op = self.operating
        kw = dict(axial_load=op.axial_load) if op.axial == "force" else dict(axial_displacement=op.axial_displacement)
        if self.tilt_free:
            kw.update(cone_tilt="free", load_offset=op.load_offset, applied_moment=tuple(op.applied_moment))
        return solve(self.geometry, radial_load=op.radial_load, inner_speed=op.speed, n_slices=self.n_slices, **kw)

    def start_state(self, qs: QuasiStaticResult | None = None) -> np.ndarray:
        """The cone at the quasi-static displacement; each roller at its quasi-static position and tilt
        in its meridional plane, orbiting at the ideal cage speed and spinning at the ideal roller speed;
        the cage concentric with the cone, its pockets centred on the rollers, at the ideal cage speed;
        then :attr:`initial`'s offsets.  With the tilt free, the cone at the 2-D solver's tilt, then moved
        onto the kernel's balance (:meth:`_balance_cone`)."""
        g = self.geometry
        qs = self.quasi_static() if qs is None else qs
        _, _, _, uc = g.roller_mass_properties()
        kin = self.ideal()
        w_cage = float(kin["cage speed [rad/s]"])
        w_spin = -float(kin["roller spin relative to cage [rad/s]"]) if self.speed else 0.0
        y = np.zeros(self.n_state)
        y[0:3] = qs.cone_displacement
        for j, psi in enumerate(qs.azimuths):
            a, r = qs.roller_displacements[j]
            beta = g.roller_axis_angle + qs.roller_tilts[j]
            radial = np.array([0.0, math.cos(psi), math.sin(psi)])
            e = np.array([math.cos(beta), 0.0, 0.0]) + math.sin(beta) * radial
            mid = np.array([a, 0.0, 0.0]) + (g.pitch_radius + r) * radial
            c = mid + uc * e
            b = L.N_CONE + j * L.NB
            y[b:b + 3] = c
            y[b + 3:b + 7] = _quat_from_x_to(e)
            y[b + 7:b + 10] = np.cross([w_cage, 0.0, 0.0], c)     # orbiting with the cage
            # body angular velocity: the orbit (about x) seen in the body frame plus the spin about e
            w_inertial = np.array([w_cage, 0.0, 0.0]) + w_spin * e
            quat_rotate_inverse(y[b + 3:b + 7].copy(), w_inertial, y[b + 10:b + 13])
        y[1:3] += np.asarray(self.initial.cone_offset, dtype=float)
        if self.has_cage:
            b = L.N_CONE + L.NB * self.n_rollers
            y[b:b + 3] = (g.cage_x, qs.cone_displacement[1], qs.cone_displacement[2])
            y[b + 1:b + 3] += np.asarray(self.initial.cage_offset, dtype=float)
            y[b + 3] = 1.0
            y[b + 10] = w_cage
        if self.tilt_free:
            y[self.tilt_index:self.tilt_index + 2] = qs.cone_tilt
            self._balance_cone(y, qs)
        return y

    def _balance_cone(self, y, qs, tol: float = 1e-11, max_iterations: int = 20) -> None:
        """With the tilt free: move the cone (y, z, the tilts; x too under an axial force) from the 2-D
        solver's equilibrium onto the compiled kernel's, in place.  The 2-D solver sees the tilt in each
        roller's plane only (phi_j = theta . e_t); its out-of-plane part (a rotation about the roller's radial
        axis, which shifts the roller across the cone by theta x) is second order and moves the kernel's
        cone moment by about 1e-3 of x_F F_r at 1e-3 rad.  Newton on the kernel's cone accelerations with a
        finite-difference Jacobian (the rollers where the 2-D solver put them) removes it, so the run starts
        without a tilt transient; the rollers keep the 2-D solver's balance (their residual accelerations
        are of the same second order, tens of m/s^2 against 1e6 m/s^2 per um of approach)."""
        if not self.fidelity.contacts:      # free bodies: nothing holds the cone, nothing to balance
            return
        args = self.args(qs)
        P = args.P[0]
        k = self.tilt_index
        idx = ([0] if self.operating.axial == "force" else []) + [1, 2, k, k + 1]
        acc = [3, 4, 5, k + 2, k + 3]
        acc = [acc[[0, 1, 2, k, k + 1].index(i)] for i in idx]
        scale = np.array([P.mc if i < 3 else P.iconet for i in idx])
        steps = np.array([1e-9 if i < 3 else 1e-8 for i in idx])
        d = np.zeros_like(y)

        def residual(state):
            K.rhs(0.0, state, args, d)
            return d[acc] * scale

        r = residual(y)
        ref = max(abs(self.operating.radial_load), abs(self.operating.axial_load), 1.0)
        for it in range(max_iterations):
            J = np.empty((len(idx), len(idx)))
            for c, (i, h) in enumerate(zip(idx, steps)):
                yp = y.copy()
                yp[i] += h
                J[:, c] = (residual(yp) - r) / h
            try:
                y[idx] -= np.linalg.solve(J, r)
            except np.linalg.LinAlgError:
                log.warning("the cone's start balance: singular Jacobian, the 2-D solver's start kept")
                return
            r = residual(y)
            # forces [N] and moments over the pitch radius [N] against the largest load
            size = np.max(np.abs(r / np.where(np.array(idx) < 3, 1.0, self.geometry.pitch_radius)))
            log.debug("cone balance, iteration %d: %.3g N", it + 1, size)
            if size < tol * ref:
                return
        log.warning("the cone's start balance stopped at %.3g N after %d iterations", size, max_iterations)

    def state_names(self) -> list[str]:
        names = [f"Cone {k} [m]" for k in "xyz"] + [f"Cone v{k} [m/s]" for k in "xyz"]
        bodies = [f"Roller {j}" for j in range(self.n_rollers)] + (["Cage"] if self.has_cage else [])
        for body in bodies:
            names += [f"{body} {k} [m]" for k in "xyz"] + [f"{body} q{k} [-]" for k in range(4)]
            names += [f"{body} v{k} [m/s]" for k in "xyz"] + [f"{body} body w{k} [rad/s]" for k in "xyz"]
        if self.tilt_free:
            names += ["Cone tilt y [rad]", "Cone tilt z [rad]", "Cone tilt rate y [rad/s]", "Cone tilt rate z [rad/s]"]
        return names

    def state_layout(self) -> dict:
        """Slices of the state vector by name: "cone", "roller j", "cage"."""
        out = {"cone": slice(0, L.N_CONE)}
        for j in range(self.n_rollers):
            out[f"roller {j}"] = slice(L.N_CONE + j * L.NB, L.N_CONE + (j + 1) * L.NB)
        if self.has_cage:
            b = L.N_CONE + self.n_rollers * L.NB
            out["cage"] = slice(b, b + L.NB)
        if self.tilt_free:
            out["cone tilt"] = slice(self.tilt_index, self.tilt_index + L.N_TILT)
        return out

    def omega_max(self) -> float:
        """An estimate of the fastest contact mode [rad/s] for the explicit step limit: sqrt(k/m) of a
        roller between its two raceways at the start's largest slice load (the slice law's tangent
        stiffness 10/9 q/delta times n_s slices, both races in parallel)."""
        qs = self.quasi_static()
        m, _, _, _ = self.geometry.roller_mass_properties()
        kl = sl.palmgren_line_constant(self.geometry.effective_length)
        q = max(float(np.max(qs.cup_loads)), 1.0)
        k = 2.0 * (10.0 / 9.0) * q / sl.approach(q, kl)
        return math.sqrt(k / m)

    @property
    def entrainment_speed(self) -> float:
        """The ideal entrainment speed u_e [m/s] the raceway films and tractions are evaluated at (floored
        at 1 mm/s for a bearing at rest)."""
        return max(float(self.ideal()["entrainment speed [m/s]"]), 1e-3)

    def raceway_strip(self, race: str, line_load: float, args=None) -> dict:
        """The Hertz strip the raceway laws see on ``race`` ("cup" or "cone") at ``line_load`` w [N/m]: its
        reduced radius R' [m], half-width b = sqrt(8 w R'/(pi E')) [m], peak pressure p0 = 2 w/(pi b) [Pa] and
        the Dowson-Toyoda central film h [m] at the ideal entrainment speed (the kernel's own evaluation)."""
        race_index = _race_index(race)
        P = (self.args() if args is None else args).P[0]
        radius = P.rxo if race_index == 0 else P.rxi
        b, p0, h0 = K.strip_film(line_load, race_index, P)
        return {"reduced radius [m]": float(radius), "half-width [m]": float(b), "peak pressure [Pa]": float(p0),
                "film [m]": float(h0)}

    def raceway_traction_coefficient(self, race: str, line_load: float, srr: float, args=None) -> float:
        """Traction coefficient [-] of the model's raceway law (``model.traction``) on ``race`` ("cup" or
        "cone") at ``line_load`` [N/m] and slide-to-roll ratio ``srr`` >= 0 (sliding speed srr u_e), as the
        kernel evaluates a slice carrying that line load (:func:`kernels.slice_traction`, its table or maps
        included): the traction curve the dynamics uses.  ``args``: the model's kernel arguments (built when
        not given)."""
        args = self.args() if args is None else args
        P = args.P[0]
        load = line_load * P.width
        force = K.slice_traction(load, _race_index(race), srr * P.ue, P, args.table, args.maps,
                                 np.zeros(1, dtype=np.int64))
        return float(force / load)

    def traction_rate(self, qs: QuasiStaticResult | None = None, args=None) -> float:
        """Decay rate [1/s] of a roller's sliding under the raceway traction's low-slip slopes k_cup, k_cone
        (0 for the laws whose slopes are orders smaller: "paper", "none", an infinitely stiff film), at the
        start's largest cup load Q on both races.  The roller's rolling-direction speed v and spin omega
        slide at the cup by s_1 = v + rho_m omega and at the cone by s_2 = v - rho_m omega (relative to
        their raceways), so that m v' = -k_1 s_1 - k_2 s_2 and I_x omega' = -rho_m (k_1 s_1 - k_2 s_2): the
        rate is the larger eigenvalue of that 2 x 2 system, lambda = (tr + sqrt(tr^2 - 4 det))/2 with
        tr = (k_1 + k_2)(1/m + rho_m^2/I_x) and det = 4 k_1 k_2 rho_m^2/(m I_x).  (Until 28 Nov 2026 the
        rate was the trace tr, an upper bound 1.5 times the eigenvalue for equal slopes on a solid roller,
        I_x = m rho^2/2: the "auto" RK4 step was 1.5 times smaller than the stability limit needs; the
        eigenvalue agrees with the right-hand side's own spectrum at the start, :meth:`spectral_step`, and
        with the bisected stability limit of ``tests/test_trb_dynamics.py``.)

        - "limited": the elastic slope; the slice slopes 2 G b_k^2 w_k/(u_e h) summed over a race give
          2 G (8 R' Q/(pi E'))/(u_e h) (b^2 = 8 w R'/(pi E') is linear in the slice load), h the kernel's
          Dowson-Toyoda film at that load (cup and cone R' and film viscosity,
          :meth:`lubedyn.dynamics.tapered.groups.Lubricant.film_viscosities`);
        - "map": (mu/s) Q/u_e, mu/s the maps' linear branch at the slide-to-roll axis' first node
          (``args``: the model's kernel arguments, built when not given)."""
        lu, g = self.lubricant, self.geometry
        law = self.fidelity.traction
        if not (law == "map" or (law == "limited" and math.isfinite(lu.shear_modulus))):
            return 0.0
        qs = self.quasi_static() if qs is None else qs
        load = max(float(np.max(qs.cup_loads)), 1.0)
        w = load / g.effective_length
        ue = self.entrainment_speed
        k = []  # cup, cone
        if law == "map":
            args = self.args(qs) if args is None else args
            s0 = float(args.P[0].tmslo)
            counter = np.zeros(1, dtype=np.int64)
            for race in (0, 1):
                k.append(K.map_traction_coefficient(race, w, s0, args.P[0], args.maps, counter) / s0 * load / ue)
        else:
            ep = g.e_prime
            for race, eta in zip(("cup", "cone"), lu.film_viscosities()):
                r = g.reduced_radius(race)
                h = r * dowson_toyoda_central(eta * ue / (ep * r), lu.pressure_viscosity * ep, w / (ep * r))
                k.append(2.0 * lu.shear_modulus * (8.0 * r * load / (math.pi * ep)) / (ue * h))
        m, ix, _, _ = g.roller_mass_properties()
        return sliding_decay_rate(k[0], k[1], m, ix, g.mean_roller_radius)

    def stable_step(self, qs: QuasiStaticResult | None = None, y0: np.ndarray | None = None, args=None) -> float:
        """An estimate of RK4's largest stable step [s]: the smaller of 2 sqrt(2)/omega_max (the contact
        modes, imaginary axis), 2.785/lambda (the traction's decay, real axis: :meth:`traction_rate`) and,
        given the start state ``y0``, the step the right-hand side's own spectrum there allows
        (:meth:`spectral_step`; ``args`` the kernel arguments when the caller has them): the closed forms know the raceway contacts and traction only, and a mode
        they miss -- the pocket films' squeeze damping with phi read as a viscosity (paper A's reading:
        a decay at 3.4e5 1/s, 8.3 us at phi = 38.44) -- once made the "auto" step unstable."""
        step = stability_limit("rk4", "imaginary") / self.omega_max()
        rate = self.traction_rate(qs, args)
        if rate > 0.0:
            step = min(step, stability_limit("rk4", "real") / rate)
        if y0 is not None:
            step = min(step, self.spectral_step(y0, args))
        return step

    def spectral_step(self, y0: np.ndarray, args=None) -> float:
        """RK4's largest stable step [s] at the state ``y0`` from the right-hand side's own spectrum
        (:func:`lubedyn.dynamics.integrators.spectral_step`: finite-difference Jacobian, about 0.04 s for 240
        states)."""
        return spectral_step(K.rhs, y0, self.args() if args is None else args, "rk4")

    # ---------------------------------------------------------------- diagnostics
    def diagnostics(self, Y, y0=None, args=None) -> dict:
        """Read sampled states ``Y`` (n, n_state) back (arrays over samples and rollers):

        - loads: "Slice loads [N]" (n, Z, 2, n_s) cup and cone; "Cup load [N]", "Cone load [N]", "Flange
          load [N]", "Pocket load [N]" (n, Z); the friction columns of :data:`layout.FRICTION_NAMES`;
        - attitude, paper A's definitions against the roller's own radial frame (x axial, r radial
          through its centre, t tangential) with e the roller axis: "Tilt [rad]" = atan2(e_r, e_x) minus
          its value at ``y0`` (rotation in the meridional plane), "Skew [rad]" = asin(e_t) minus its
          value at ``y0`` (out of it); ``y0`` defaults to the first sample;
        - speeds: "Orbital speed [rad/s]" of the centre about x, "Spin speed [rad/s]" (the angular
          velocity relative to the orbiting frame, along e), "Roller slip [-]" eq. 52 (omega_ideal -
          omega)/omega_ideal of the orbital speed and "Spin slip [-]" of the spin against the geometry's
          ideal kinematics (docs/paper_a.md; NaN at rest);
        - the cage: "Cage speed [rad/s]" (about x, inertial), "Cage slip [-]", "Cage centre [m]" (n, 2)
          relative to the cone's, "Guide land load [N]";
        - the terms of each roller's tilt moment, "Tilt moment, cup normal [N m]" etc. (n, Z)
          (:data:`layout.TILT_MOMENT_NAMES`, :mod:`kernels` "Tilt moment");
        - "Cone force [N]" (n, 3) of the rollers and cage on the cone; with the cone's tilt free, "Cone moment
          [N m]" (n, 3), their moment about its reference point, and "Cone tilt [rad]" (n, 2) theta_y,
          theta_z."""
        Y = np.atleast_2d(np.asarray(Y, dtype=float))
        args = self.args() if args is None else args
        loads, slices, friction, cage, cone = K.forces_many(np.ascontiguousarray(Y), args)
        out = {"Slice loads [N]": slices, "Cone force [N]": cone[:, :3]}
        if self.tilt_free:
            out["Cone moment [N m]"] = cone[:, 3:]
            out["Cone tilt [rad]"] = Y[:, self.tilt_index:self.tilt_index + 2]
        for k, name in enumerate(L.LOAD_NAMES):
            out[name] = loads[:, :, k]
        for k, name in enumerate(L.FRICTION_NAMES):
            out[name] = friction[:, :, k]
        y0 = Y[0] if y0 is None else np.asarray(y0, dtype=float)
        tilt, skew, orbital, spin = attitude(np.vstack([y0[None, :], Y]), self.n_rollers)
        out["Tilt [rad]"] = tilt[1:] - tilt[0]
        out["Skew [rad]"] = skew[1:] - skew[0]
        out["Orbital speed [rad/s]"], out["Spin speed [rad/s]"] = orbital[1:], spin[1:]
        kin = self.ideal()
        wc, ws = kin["cage speed [rad/s]"], -kin["roller spin relative to cage [rad/s]"]
        with np.errstate(divide="ignore", invalid="ignore"):
            out["Roller slip [-]"] = (wc - orbital[1:]) / wc if wc else np.full_like(orbital[1:], np.nan)
            out["Spin slip [-]"] = (ws - spin[1:]) / ws if ws else np.full_like(spin[1:], np.nan)
        if self.has_cage:
            b = L.N_CONE + L.NB * self.n_rollers
            q = Y[:, b + 3:b + 7] / np.linalg.norm(Y[:, b + 3:b + 7], axis=1)[:, None]
            # x component of R(q) omega_body: the first row of the rotation matrices
            out["Cage speed [rad/s]"] = np.einsum("nj,nj->n", _matrices(q)[:, 0, :], Y[:, b + 10:b + 13])
            with np.errstate(divide="ignore", invalid="ignore"):
                out["Cage slip [-]"] = (wc - out["Cage speed [rad/s]"]) / wc if wc else np.full(len(Y), np.nan)
            out["Cage centre [m]"] = Y[:, b + 1:b + 3] - Y[:, 1:3]
            out["Guide land load [N]"] = cage[:, 3]
            out["Side beam load [N]"] = cage[:, 4]
        return out


def annulus_inertia(mass: float, radii_squared: float, width: float) -> tuple[float, float]:
    """(polar, transverse about its centre) moments of inertia [kg m^2] of a ring of ``mass`` [kg], outer and
    inner radii with r_o^2 + r_i^2 = ``radii_squared`` [m^2] and axial ``width`` [m]: m (r_o^2 + r_i^2)/2
    and m (3 (r_o^2 + r_i^2) + w^2)/12."""
    return 0.5 * mass * radii_squared, mass * (3.0 * radii_squared + width * width) / 12.0


def attitude(Y, n_rollers):
    """(tilt angle beta [rad], skew [rad], orbital speed [rad/s], spin relative to the orbit [rad/s]) per
    sample and roller: e the roller axis R(q) e_x, split in the roller's radial frame (x, r, t):
    beta = atan2(e_r, e_x), skew = asin(e_t); orbital speed (c x v)_x / |c_yz|^2; spin (w - w_orb e_x).e
    with w the inertial angular velocity R(q) omega_body."""
    n = Y.shape[0]
    beta, skew, orbital, spin = (np.empty((n, n_rollers)) for _ in range(4))
    for j in range(n_rollers):
        b = L.N_CONE + j * L.NB
        c, q, v, wb = Y[:, b:b + 3], Y[:, b + 3:b + 7], Y[:, b + 7:b + 10], Y[:, b + 10:b + 13]
        q = q / np.linalg.norm(q, axis=1)[:, None]
        R = _matrices(q)
        e = R[:, :, 0]
        w = np.einsum("nij,nj->ni", R, wb)
        rr = np.hypot(c[:, 1], c[:, 2])
        er = (e[:, 1] * c[:, 1] + e[:, 2] * c[:, 2]) / rr
        et = (-e[:, 1] * c[:, 2] + e[:, 2] * c[:, 1]) / rr
        beta[:, j] = np.arctan2(er, e[:, 0])
        skew[:, j] = np.arcsin(np.clip(et, -1.0, 1.0))
        orbital[:, j] = (c[:, 1] * v[:, 2] - c[:, 2] * v[:, 1]) / rr**2
        spin[:, j] = np.einsum("ni,ni->n", w, e) - orbital[:, j] * e[:, 0]
    return beta, skew, orbital, spin


def _matrices(q):
    """(n, 3, 3) rotation matrices of unit quaternions q (n, 4), scalar first."""
    w, x, y, z = q.T
    return np.stack([
        np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], axis=1),
        np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], axis=1),
        np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], axis=1)], axis=1)


def _quat_from_x_to(e) -> np.ndarray:
    """Unit quaternion (scalar first) of the shortest rotation taking e_x to the unit vector e."""
    x = np.array([1.0, 0.0, 0.0])
    axis = np.cross(x, e)
    s = np.linalg.norm(axis)
    c = float(x @ e)
    if s < 1e-15:
        return np.array([1.0, 0.0, 0.0, 0.0])
    half = 0.5 * math.atan2(s, c)
    return np.concatenate([[math.cos(half)], math.sin(half) * axis / s])
