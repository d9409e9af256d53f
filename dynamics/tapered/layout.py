"""The tapered roller bearing's state layout, option codes and the indices of its packed parameters and
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

N_CONE, NB, N_TILT = 6, 13, 4
# offsets inside a body block
B_C, B_Q, B_V, B_W = 0, 3, 7, 10

# option codes (the float parameter vector carries them as floats)
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

# float parameters (the first 54 are those of issue 23's first step, in that order)
(P_Z, P_NS, P_M, P_IX, P_IY, P_MC, P_OMEGA, P_FA, P_FR, P_AXIAL, P_KW, P_KF, P_ALPHA, P_RS, P_US, P_UC,
 P_CUPX, P_CUPR, P_CUPNX, P_CUPNR, P_CONX, P_CONR, P_CONNX, P_CONNR, P_FLX, P_FLR, P_FLNX, P_FLNR,
 P_CONTACTS, P_QSTAB, P_TRACTION, P_ETA, P_PVC, P_EP, P_RXO, P_RXI, P_UE, P_WIDTH,
 P_CAGE, P_MCG, P_ICX, P_ICT, P_POCKET, P_LEN, P_RHOM, P_HCRIT, P_KH, P_CH, P_MUBD, P_SWITCH, P_RLAND, P_CLAND,
 P_BLAND, P_HLAND,
 # issue 23 part 2: options, gravity, grease rheology, flange friction, contact-only pocket and land
 P_POCKETMODE, P_LANDMODE, P_GRAV,
 P_TAUY, P_PHI0, P_NEXP, P_ALPHAG, P_TAUL0, P_GAMMAL, P_DR,
 P_FFRIC, P_MUA, P_FBC, P_FCC, P_LAMBDA, P_HRIB, P_FA1, P_FB1, P_FP01,
 P_KPOCKET, P_KLAND, P_VREG,
 # the film's shear modulus of the limited raceway traction (elastic_limited)
 P_GSHEAR,
 # side beams (eqs. 39-40): axial clearance (0: none, the cage's axial DOF held), pocket centre's radius
 # and axial offset from the cage centre, the roller axis angle, end diameters, the beams' thickness
 P_SIDEGAP, P_PITCH, P_POCKX, P_BETA0, P_DLARGE, P_DSMALL, P_HSIDE,
 # the cone's tilt: flag (CONE_TILTS), offset of the state's tilt block, transverse and polar moments of
 # inertia of the cone, the radial load's axial position from the cone's reference point, the applied
 # moment (y, z) about it, the guide land's axial position from the cone's reference point
 P_TILT, P_TILTAT, P_ICONET, P_ICONEX, P_LOADX, P_MY, P_MZ, P_LANDX,
 # the limited traction's tables (TaperedBearing.traction_tables), appended to P after P_SIZE: a flag, the
 # node counts along sliding speed and line load, and the offset of each raceway's block (cup, cone); a
 # block is [log v nodes (n0), log w nodes (n1), Hermite data (4 x n0 x n1)]
 P_TTAB, P_TTN0, P_TTN1, P_TTOFF0, P_TTOFF1,
 # the roller EHL maps' traction at the run's entrainment speed (TaperedBearing.map_traction_tables,
 # traction "map"), appended after P_SIZE: node counts along line load and the maps' slide-to-roll
 # coordinate, the offset of each raceway's block (cup, cone), the normalised-slip map (a, b, centre of
 # lubedyn.film_points.normalised_slip) and the slide-to-roll axis' ends; a block is [log w nodes (nw),
 # log x nodes (nx), Hermite data of log s_t (2 x nw), Hermite data of log G (4 x nw x nx)]
 P_TMNW, P_TMNX, P_TMOFF0, P_TMOFF1, P_TMA, P_TMB, P_TMCEN, P_TMSLO, P_TMSHI) = range(106)
P_SIZE = 106

# per-roller loads of loads_many / forces: columns
LOAD_NAMES = ("Cup load [N]", "Cone load [N]", "Flange load [N]", "Pocket load [N]")
L_CUP, L_CONE, L_FLANGE, L_POCKET = range(4)
# per-roller friction diagnostics of forces(): columns
FRICTION_NAMES = ("Cup traction [N]", "Cone traction [N]", "Flange friction [N]", "Pocket friction [N]",
                  "Cup sliding speed max [m/s]", "Cone sliding speed max [m/s]", "Flange sliding speed [m/s]")
N_FRICTION = 7
CAGE_NAMES = ("Cage force on cage y [N]", "Cage force on cage z [N]", "Cage torque x [N m]", "Guide land load [N]",
              "Side beam load [N]")
N_CAGE_DIAG = 5
