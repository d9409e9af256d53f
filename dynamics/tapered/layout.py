"""The tapered roller bearing's state layout, option codes, the record of its parameters (read by name) and
diagnostics.

Part of :mod:`lubedyn.dynamics.tapered` (:mod:`lubedyn.dynamics.tapered.kernels` gives the equations).  State::

    [cone x, y, z, vx, vy, vz]                                  N_CONE = 6 (the cone's spin is prescribed)
    [roller j: c (3), q (4), v (3), omega_body (3)] x Z          NB = 13 per roller
    [cage: c (3), q (4), v (3), omega_body (3)]                  13 (present unless pocket = "none")
    [cone tilt: theta_y, theta_z, theta_y', theta_z']             N_TILT = 4 (present with cone_tilt = "free")

c the mass centre, q the unit quaternion (scalar first) from the body frame (x along the body's axis)
to the inertial frame (x the bearing axis, the cup fixed), omega_body the body-frame angular velocity.
The cone's tilt (option ``operating.cone_tilt = "free"``) is appended after the last body, so the locked
layout (and every index above) is the same with and without it: theta = (0, theta_y, theta_z) the small
rotation vector of the cone about its reference point (:mod:`lubedyn.dynamics.tapered.kernels`).
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ..groups import record_row

N_CONE, NB, N_TILT = 6, 13, 4
# offsets inside a body block
B_C, B_Q, B_V, B_W = 0, 3, 7, 10

# option codes (the parameter record carries them as floats)
AXIAL_MODES = {"locked": 0, "force": 1}   # "locked": held at operating.axial_displacement
AXIAL_LOCKED, AXIAL_FORCE = 0.0, 1.0
CONE_TILTS = {"locked": 0, "free": 1}    # "locked": the shaft's other support carries the moment
TRACTIONS = {"none": 0, "paper": 1, "limited": 2, "map": 3}
TRACTION_NONE, TRACTION_PAPER, TRACTION_LIMITED, TRACTION_MAP = 0.0, 1.0, 2.0, 3.0
FLANGE_FRICTIONS = {"none": 0, "paper": 1, "load_share": 2}     # eqs. 22-23 as printed / fluid load share
POCKETS = {"none": 0, "contact": 1, "film": 2}                  # "film": lubedyn.lubrication.laws.cage.pocket_force
POCKET_NONE, POCKET_CONTACT, POCKET_FILM = 0.0, 1.0, 2.0
LANDS = {"none": 0, "contact": 1, "film": 2}                    # "film": short bearing + Couette drag + boundary
LAND_NONE, LAND_CONTACT, LAND_FILM = 0.0, 1.0, 2.0

# the bearing's parameters: one named float64 field each (option codes as floats), the record of
# PARAMETER_DTYPE the kernels read by name (P.kw); the tables are their own arrays (TractionTable,
# MapTable), not appended to it
PARAMETERS = (
    ('z', 'number of rollers Z'),
    ('ns', 'slices per roller n_s'),
    ('m', 'roller mass [kg]'),
    ('ix', "roller's axial moment of inertia [kg m^2]"),
    ('iy', "roller's transverse moment of inertia [kg m^2]"),
    ('mc', 'cone mass [kg]'),
    ('omega', 'cone speed [rad/s]'),
    ('fa', 'axial load [N]'),
    ('fr', 'radial load [N]'),
    ('axial', 'axial mode (AXIAL_MODES)'),
    ('kw', 'slice load constant (Palmgren, per slice)'),
    ('kf', 'flange Hertz constant [N/m^1.5]'),
    ('alpha', 'contact damping alpha_e (eq. 11) [s/m]'),
    ('rs', 'roller end sphere radius [m]'),
    ('us', "end sphere centre's axial offset from the roller's mid-point [m]"),
    ('uc', "mass centre's axial offset from the mid-point [m]"),
    ('cupx', 'cup raceway point x [m]'),
    ('cupr', 'cup raceway point r [m]'),
    ('cupnx', 'cup raceway normal x'),
    ('cupnr', 'cup raceway normal r'),
    ('conx', 'cone raceway point x [m]'),
    ('conr', 'cone raceway point r [m]'),
    ('connx', 'cone raceway normal x'),
    ('connr', 'cone raceway normal r'),
    ('flx', 'flange (rib) point x [m]'),
    ('flr', 'flange point r [m]'),
    ('flnx', 'flange normal x'),
    ('flnr', 'flange normal r'),
    ('contacts', '1: contacts on, 0: free bodies'),
    ('qstab', 'quaternion drift stabilisation [1/s]'),
    ('traction', 'raceway traction law (TRACTIONS)'),
    ('eta', 'viscosity [Pa s]'),
    ('etao', 'cup raceway film viscosity [Pa s] (the Dowson-Toyoda film of the cup slices)'),
    ('etai', 'cone raceway film viscosity [Pa s] (the Dowson-Toyoda film of the cone slices)'),
    ('pvc', 'pressure-viscosity coefficient [1/Pa]'),
    ('ep', "E' of the raceway contacts [Pa]"),
    ('rxo', 'cup reduced radius [m]'),
    ('rxi', 'cone reduced radius [m]'),
    ('ue', 'ideal entrainment speed [m/s]'),
    ('width', 'slice width [m]'),
    ('cage', '1: the cage is present'),
    ('mcg', 'cage mass [kg]'),
    ('icx', 'cage polar moment of inertia [kg m^2]'),
    ('ict', 'cage transverse moment of inertia [kg m^2]'),
    ('pocket', 'pocket clearance [m]'),
    ('len', 'roller effective length [m]'),
    ('rhom', 'mean roller radius [m]'),
    ('hcrit', 'pocket critical film [m]'),
    ('kh', 'pocket film stiffness'),
    ('ch', 'pocket film damping'),
    ('mubd', 'boundary friction coefficient'),
    ('switch', 'pocket film switch (POCKET_SWITCHES)'),
    ('rland', 'guide land radius [m]'),
    ('cland', 'guide land radial clearance [m]'),
    ('bland', 'guide land width [m]'),
    ('hland', 'land critical film [m]'),
    ('pocketmode', 'pocket level (POCKETS)'),
    ('landmode', 'guide land level (LANDS)'),
    ('grav', 'gravity [m/s^2]'),
    ('tauy', 'grease yield stress [Pa]'),
    ('phi0', 'grease consistency [Pa s^n]'),
    ('nexp', 'grease flow exponent'),
    ('alphag', 'grease pressure-viscosity [1/Pa]'),
    ('taul0', 'limiting shear stress [Pa]'),
    ('gammal', 'limiting shear slope'),
    ('dr', 'yield rate [1/s]'),
    ('ffric', 'flange friction law (FLANGE_FRICTIONS)'),
    ('mua', 'asperity friction coefficient'),
    ('fbc', 'asperity share B'),
    ('fcc', 'asperity share C'),
    ('lam', 'film parameter h/sigma of the rib'),
    ('hrib', 'rib film [m]'),
    ('fa1', 'rib Hertz semi-axis a at 1 N [m]'),
    ('fb1', 'rib Hertz semi-axis b at 1 N [m]'),
    ('fp01', 'rib Hertz peak pressure at 1 N [Pa]'),
    ('kpocket', 'contact-only pocket line constant'),
    ('kland', 'contact-only land line constant'),
    ('vreg', 'friction regularisation speed [m/s]'),
    ('gshear', 'film shear modulus G [Pa] (limited traction)'),
    ('sidegap', 'side beam axial clearance [m] (0: none)'),
    ('pitch', 'pitch radius [m]'),
    ('pockx', "pocket centre's axial offset from the cage centre [m]"),
    ('beta0', 'roller axis angle [rad]'),
    ('dlarge', 'large end diameter [m]'),
    ('dsmall', 'small end diameter [m]'),
    ('hside', 'side beam thickness [m]'),
    ('tilt', 'cone tilt (CONE_TILTS)'),
    ('tiltat', "offset of the state's tilt block"),
    ('iconet', 'cone transverse moment of inertia [kg m^2]'),
    ('iconex', 'cone polar moment of inertia [kg m^2]'),
    ('loadx', "radial load's axial position [m]"),
    ('my', 'applied moment y [N m]'),
    ('mz', 'applied moment z [N m]'),
    ('landx', "guide land's axial position [m]"),
    ('ttab', "1: the limited traction's tables are given (TractionTable)"),
    ('tma', "traction maps' normalised slip a"),
    ('tmb', "traction maps' normalised slip b"),
    ('tmcen', "traction maps' normalised slip centre"),
    ('tmslo', "traction maps' slide-to-roll axis, first node"),
    ('tmshi', "traction maps' slide-to-roll axis, last node"),
)
PARAMETER_DTYPE = np.dtype([(name, np.float64) for name, _ in PARAMETERS], align=True)


def parameter_record(values: dict) -> np.recarray:
    """The kernels' parameter record (:data:`PARAMETER_DTYPE`, read by name: ``P.kw``) from ``values``
    {field: number}, as a record array of one row (the kernels read its row, ``P = args.P[0]``: numba
    takes an array from Python at the cost of any array, a record scalar costs ten times more): every field of :data:`PARAMETERS` and no other, else a :class:`DynamicsInputError`
    naming the field (a misspelt or forgotten parameter is not left at 0)."""
    return record_row(PARAMETER_DTYPE, values, "the tapered bearing's parameter record", dict(PARAMETERS), "lubedyn.dynamics.tapered.layout.PARAMETERS")


class TractionTable(NamedTuple):
    """The limited traction's tables of both raceways (index 0 cup, 1 cone;
    :meth:`lubedyn.dynamics.tapered.model.TaperedBearing.traction_tables`): the prepared log nodes of the
    sliding speed (2, n0) and of the line load (2, n1), and the cubic Hermite data of the log traction
    (2, 4, n0, n1).  Empty (n0 = n1 = 0) when the model has none (``P.ttab`` = 0)."""

    speeds: np.ndarray
    loads: np.ndarray
    data: np.ndarray


class MapTable(NamedTuple):
    """The roller EHL maps' traction at the run's entrainment speed, both raceways (0 cup, 1 cone;
    :meth:`lubedyn.dynamics.tapered.model.TaperedBearing.map_traction_tables`): log line-load nodes (2, nw),
    log slide-to-roll coordinate nodes (2, nx), Hermite data of log s_t (2, 2, nw) and of log G
    (2, 4, nw, nx).  Empty when the raceway traction is not "map"."""

    loads: np.ndarray
    slips: np.ndarray
    shift: np.ndarray
    values: np.ndarray


def no_traction_table() -> TractionTable:
    return TractionTable(np.zeros((2, 0)), np.zeros((2, 0)), np.zeros((2, 4, 0, 0)))


def no_map_table() -> MapTable:
    return MapTable(np.zeros((2, 0)), np.zeros((2, 0)), np.zeros((2, 2, 0)), np.zeros((2, 4, 0, 0)))


class KernelArgs(NamedTuple):
    """The arguments of :func:`lubedyn.dynamics.tapered.kernels.rhs`: the parameter record ``P``
    (:func:`parameter_record`), the slices' axial coordinates ``U`` and radii ``RHO`` (n_s), the limited
    traction's tables and the traction maps' tables (empty when not used: one compiled variant)."""

    P: np.recarray
    U: np.ndarray
    RHO: np.ndarray
    table: TractionTable
    maps: MapTable

# per-roller loads of loads_many / forces: columns
LOAD_NAMES = ("Cup load [N]", "Cone load [N]", "Flange load [N]", "Pocket load [N]")
L_CUP, L_CONE, L_FLANGE, L_POCKET = range(4)
# per-roller friction diagnostics of forces(): columns
# and the terms of the contacts' moment on the roller about its tilt axis through its mass centre
# (lubedyn.dynamics.tapered.kernels, "Tilt moment"; positive turns the axis from x towards r, the "Tilt [rad]" sense)
TILT_MOMENT_NAMES = ("Tilt moment, cup normal [N m]", "Tilt moment, cone normal [N m]",
                     "Tilt moment, cup traction [N m]", "Tilt moment, cone traction [N m]",
                     "Tilt moment, flange normal [N m]", "Tilt moment, flange friction [N m]",
                     "Tilt moment, cage [N m]")
FRICTION_NAMES = ("Cup traction [N]", "Cone traction [N]", "Flange friction [N]", "Pocket friction [N]",
                  "Cup sliding speed max [m/s]", "Cone sliding speed max [m/s]", "Flange sliding speed [m/s]",
                  *TILT_MOMENT_NAMES)
N_FRICTION = 14
F_TILT = 7          # the first tilt-moment column
CAGE_NAMES = ("Cage force on cage y [N]", "Cage force on cage z [N]", "Cage torque x [N m]", "Guide land load [N]",
              "Side beam load [N]")
N_CAGE_DIAG = 5


def example_args() -> KernelArgs:
    """Kernel arguments of the types every model's :class:`KernelArgs` has (a zero record, one slice,
    no tables): what compiling a kernel needs before the model is built
    (:func:`lubedyn.dynamics.specialise.compile_in_background`)."""
    return KernelArgs(parameter_record(dict.fromkeys(PARAMETER_DTYPE.names, 0.0)), np.zeros(1), np.zeros(1), no_traction_table(), no_map_table())
