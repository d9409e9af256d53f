"""The tapered roller bearing as a compiled right-hand side (issue 23, first step): parameters, the start
state from the quasi-static equilibrium, and the state's names.

:class:`TaperedBearing` packs a :class:`lubrication.laws.tapered.TaperedRollerGeometry` and the operating
point into the arrays of :func:`dynamics.tapered.kernels.rhs` (``args()``), and places the cone and the
rollers where :func:`dynamics.tapered.quasistatic.solve` finds them in equilibrium, the rollers orbiting
at the ideal cage speed and spinning at their ideal speed (``start_state``), so a run does not begin with
an impact.  What this step leaves out (traction, cage, gravity) is listed in the kernels' docstring.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from lubrication.errors import InputError
from lubrication.laws import slices as sl
from lubrication.laws.cage import POCKET_SWITCHES
from lubrication.laws.tapered import TaperedRollerGeometry

from ..rotations import quat_rotate_inverse
from . import kernels as K
from .quasistatic import QuasiStaticResult, solve

AXIAL_MODES = ("locked", "force")
TRACTIONS = ("none", "paper")


@dataclass(frozen=True)
class TaperedBearing:
    """``geometry``; ``n_slices`` per roller and raceway; the cone's ``speed`` [rad/s], ``radial_load``
    [N] (along +y), ``axial`` = "locked" (held at the start's axial displacement) or "force" (free under
    ``axial_load`` [N], closing); ``cone_mass`` [kg] (assumed: paper A gives none); ``damping_alpha``
    alpha_e [s/m] of eq. 11 (slices and flange); ``contacts`` False: free rollers (a test of the
    equations of motion); ``quaternion_stabilisation`` [1/s]; ``traction`` "none" or "paper" (eq. 12)
    with the film's ``viscosity`` [Pa s] and ``pressure_viscosity`` [1/Pa] (defaults: paper A's assumed
    base oil and the grease's alpha, :mod:`coupling.parameters.wu2018`); ``cage`` True: the cage with
    its pockets and guide land (:mod:`lubrication.laws.cage`), which needs ``cage_mass`` [kg] and the
    pocket's ``pocket_critical_film`` [m], ``pocket_stiffness`` [N/m], ``pocket_damping`` [N s/m],
    ``boundary_friction`` [-], ``pocket_switch`` ("continuous" or "paper"), ``land_critical_film`` [m]
    (paper A gives none of them: :mod:`coupling.parameters.wu2018` holds the assumed values)."""

    geometry: TaperedRollerGeometry
    n_slices: int = 20
    speed: float = 0.0
    radial_load: float = 0.0
    axial: str = "locked"
    axial_load: float = 0.0
    axial_displacement: float = 0.0
    cone_mass: float = 5.0
    damping_alpha: float = 0.16
    contacts: bool = True
    quaternion_stabilisation: float = 10.0
    traction: str = "none"
    viscosity: float = 0.1
    pressure_viscosity: float = 4.662e-8
    cage: bool = False
    cage_mass: float | None = None
    pocket_critical_film: float | None = None
    pocket_stiffness: float | None = None
    pocket_damping: float | None = None
    boundary_friction: float | None = None
    pocket_switch: str = "continuous"
    land_critical_film: float | None = None

    def __post_init__(self):
        if self.traction not in TRACTIONS:
            raise InputError(f"traction = {self.traction!r} is not allowed; choose one of {', '.join(TRACTIONS)}")
        if self.axial not in AXIAL_MODES:
            raise InputError(f"axial = {self.axial!r} is not allowed; choose one of {', '.join(AXIAL_MODES)}")
        for key in ("cone_mass",):
            if not getattr(self, key) > 0.0:
                raise InputError(f"{key} = {getattr(self, key)!r} must be > 0")
        for key in ("damping_alpha", "radial_load", "axial_load", "speed"):
            if not getattr(self, key) >= 0.0:
                raise InputError(f"{key} = {getattr(self, key)!r} must be >= 0")
        if self.cage:
            for key in ("cage_mass", "pocket_critical_film", "pocket_stiffness", "pocket_damping",
                        "boundary_friction", "land_critical_film"):
                value = getattr(self, key)
                if value is None or not value >= 0.0:
                    raise InputError(f"{key} = {value!r} must be given (>= 0) with cage = True")
            if self.pocket_switch not in POCKET_SWITCHES:
                raise InputError(f"pocket_switch = {self.pocket_switch!r} is not allowed; choose one of "
                                 f"{', '.join(POCKET_SWITCHES)}")
        if int(self.n_slices) != self.n_slices or self.n_slices < 1:
            raise InputError(f"n_slices = {self.n_slices!r} must be an integer >= 1")

    @property
    def n_rollers(self) -> int:
        return int(self.geometry.n_rollers)

    def args(self):
        """``(P, U, RHO)`` of :func:`dynamics.tapered.kernels.rhs`."""
        g = self.geometry
        u, _ = g.slices(self.n_slices)
        rho = np.asarray(g.roller_radius(u), dtype=float)
        m, ix, iy, uc = g.roller_mass_properties()
        P = np.zeros(K.P_SIZE)
        P[K.P_Z], P[K.P_NS] = self.n_rollers, self.n_slices
        P[K.P_M], P[K.P_IX], P[K.P_IY], P[K.P_UC] = m, ix, iy, uc
        P[K.P_MC], P[K.P_OMEGA] = self.cone_mass, self.speed
        P[K.P_FA], P[K.P_FR] = self.axial_load, self.radial_load
        P[K.P_AXIAL] = K.AXIAL_FORCE if self.axial == "force" else K.AXIAL_LOCKED
        P[K.P_KW] = sl.slice_constant(sl.palmgren_line_constant(g.effective_length), self.n_slices)
        P[K.P_KF] = g.flange_hertz_constant()
        P[K.P_ALPHA] = self.damping_alpha
        P[K.P_RS], P[K.P_US] = g.end_sphere_radius, g.sphere_center_u
        (P[K.P_CUPX], P[K.P_CUPR]), (P[K.P_CUPNX], P[K.P_CUPNR]) = g.cup_point, g.cup_normal
        (P[K.P_CONX], P[K.P_CONR]), (P[K.P_CONNX], P[K.P_CONNR]) = g.cone_point, g.cone_normal
        (P[K.P_FLX], P[K.P_FLR]), (P[K.P_FLNX], P[K.P_FLNR]) = g.flange_point, g.flange_normal
        P[K.P_CONTACTS] = 1.0 if self.contacts else 0.0
        P[K.P_QSTAB] = self.quaternion_stabilisation
        P[K.P_TRACTION] = K.TRACTION_PAPER if self.traction == "paper" else K.TRACTION_NONE
        P[K.P_ETA], P[K.P_PVC], P[K.P_EP] = self.viscosity, self.pressure_viscosity, g.e_prime
        P[K.P_RXO], P[K.P_RXI] = g.reduced_radius("cup"), g.reduced_radius("cone")
        P[K.P_UE] = max(float(g.kinematics(self.speed)["entrainment speed [m/s]"]), 1e-3)
        P[K.P_WIDTH] = g.effective_length / self.n_slices
        if self.cage:
            ro, ri, h = 0.5 * g.cage_outer_diameter, 0.5 * g.cage_inner_diameter, g.cage_thickness
            P[K.P_CAGE], P[K.P_MCG] = 1.0, self.cage_mass
            # the cage ring as an annulus (its bars' share of the inertia is not known: assumed)
            P[K.P_ICX] = 0.5 * self.cage_mass * (ro * ro + ri * ri)
            P[K.P_ICT] = self.cage_mass * (3.0 * (ro * ro + ri * ri) + h * h) / 12.0
            P[K.P_POCKET], P[K.P_LEN], P[K.P_RHOM] = g.pocket_clearance, g.effective_length, g.mean_roller_radius
            P[K.P_HCRIT], P[K.P_KH], P[K.P_CH] = self.pocket_critical_film, self.pocket_stiffness, self.pocket_damping
            P[K.P_MUBD], P[K.P_SWITCH] = self.boundary_friction, POCKET_SWITCHES[self.pocket_switch]
            P[K.P_RLAND], P[K.P_CLAND] = g.land_radius, 0.5 * g.guide_land_clearance
            P[K.P_BLAND], P[K.P_HLAND] = g.guide_land_width, self.land_critical_film
        return P, np.ascontiguousarray(u), np.ascontiguousarray(rho)

    def quasi_static(self) -> QuasiStaticResult:
        """The equilibrium the run starts from (same loads, slices and speed)."""
        kw = dict(axial_load=self.axial_load) if self.axial == "force" else dict(
            axial_displacement=self.axial_displacement)
        return solve(self.geometry, radial_load=self.radial_load, inner_speed=self.speed, n_slices=self.n_slices,
                     **kw)

    def start_state(self, qs: QuasiStaticResult | None = None) -> np.ndarray:
        """The cone at the quasi-static displacement; each roller at its quasi-static position and tilt
        in its meridional plane, orbiting at the ideal cage speed and spinning at the ideal roller speed."""
        g = self.geometry
        qs = self.quasi_static() if qs is None else qs
        _, _, _, uc = g.roller_mass_properties()
        kin = g.kinematics(self.speed)
        w_cage = float(kin["cage speed [rad/s]"])
        w_spin = -float(kin["roller spin relative to cage [rad/s]"]) if self.speed else 0.0
        y = np.zeros(K.N_CONE + K.NB * (self.n_rollers + (1 if self.cage else 0)))
        y[0:3] = qs.cone_displacement
        for j, psi in enumerate(qs.azimuths):
            a, r = qs.roller_displacements[j]
            beta = g.roller_axis_angle + qs.roller_tilts[j]
            radial = np.array([0.0, math.cos(psi), math.sin(psi)])
            e = np.array([math.cos(beta), 0.0, 0.0]) + math.sin(beta) * radial
            mid = np.array([a, 0.0, 0.0]) + (g.pitch_radius + r) * radial
            c = mid + uc * e
            b = K.N_CONE + j * K.NB
            y[b:b + 3] = c
            y[b + 3:b + 7] = _quat_from_x_to(e)
            y[b + 7:b + 10] = np.cross([w_cage, 0.0, 0.0], c)     # orbiting with the cage
            # body angular velocity: the orbit (about x) seen in the body frame plus the spin about e
            w_inertial = np.array([w_cage, 0.0, 0.0]) + w_spin * e
            quat_rotate_inverse(y[b + 3:b + 7].copy(), w_inertial, y[b + 10:b + 13])
        if self.cage:   # concentric with the cone, pockets on the rollers, turning at the ideal cage speed
            b = K.N_CONE + K.NB * self.n_rollers
            y[b:b + 3] = (g.cage_x, qs.cone_displacement[1], qs.cone_displacement[2])
            y[b + 3] = 1.0
            y[b + 10] = w_cage
        return y

    def state_names(self) -> list[str]:
        names = [f"Cone {k} [m]" for k in "xyz"] + [f"Cone v{k} [m/s]" for k in "xyz"]
        for j in range(self.n_rollers):
            names += [f"Roller {j} {k} [m]" for k in "xyz"] + [f"Roller {j} q{k} [-]" for k in range(4)]
            names += [f"Roller {j} v{k} [m/s]" for k in "xyz"] + [f"Roller {j} body w{k} [rad/s]" for k in "xyz"]
        if self.cage:
            names += [f"Cage {k} [m]" for k in "xyz"] + [f"Cage q{k} [-]" for k in range(4)]
            names += [f"Cage v{k} [m/s]" for k in "xyz"] + [f"Cage body w{k} [rad/s]" for k in "xyz"]
        return names


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
