"""The cage-less bearing's state layout, option codes and the indices of its packed parameters and diagnostics.

Part of :mod:`lubedyn.dynamics.cageless` (the package docstring gives the overview)."""
from __future__ import annotations

from .. import contacts as C

DOFS = {"planar": 0, "6dof": 1}
SCENARIOS = {"steady": 0, "drop": 1, "free": 2}
RACES = {"outer": 0, "inner": 1}
TRACTIONS = {"closed_form": 0, "map": 1}
RACE_FILMS = {"none": 0, "closed_form": 1}
MAP_SPEED_AXES = {"approach_speed": C.MAP_AXIS_APPROACH, "squeeze_number": C.MAP_AXIS_SQUEEZE,
                  "polar": C.MAP_AXIS_POLAR}
# traction maps start at a slide-to-roll ratio > 0 (lubedyn.film_points, "Traction axis"): below the
# first node the kernel takes mu linear in the SRR (tests/test_traction_map.py checks this flag)
TRACTION_MAP_BELOW_AXIS = "linear"
N_RING = 9
NB_PLANAR, NB_6DOF = 6, 13

# integer options
I_Z, I_DOF, I_FILM, I_DRIVE, I_TRACTION, I_BALLBALL, I_NSLOT = range(7)
I_SIZE = 7
ARG_COUNTER = 9  # position of the clamp counter in the args tuple
# float parameters
(P_D, P_RB, P_ROC, P_RIC, P_RO, P_RI, P_MB, P_JB, P_MR, P_JR, P_JROT, P_KI, P_KO, P_ALPHA, P_MU, P_SRR, P_VREG,
 P_FX, P_FY, P_FZ, P_G, P_OMEGA_FIX, P_MUROT, P_RC, P_WREG, P_NROT, P_SW, P_SL, P_SBLEND, P_KEO, P_KEI, P_REO,
 P_REI, P_QSTAB, P_HCI, P_HCO) = range(36)
P_SIZE = 36

# per-ball diagnostics of forces()
DIAG_NAMES = (
    "Inner race load [N]", "Outer race load [N]", "Inner contact angle [rad]", "Outer contact angle [rad]",
    "Inner slide-to-roll ratio [-]", "Outer slide-to-roll ratio [-]", "Inner sliding speed [m/s]",
    "Outer sliding speed [m/s]", "Slot edge load [N]", "Ball-ball force x [N]", "Ball-ball force y [N]",
    "Ball-ball force z [N]", "Ball-ball normal force [N]", "Ball-ball friction force [N]", "Ball-ball gap [m]",
    "Ball-ball film thickness [m]", "Ball-ball phase [-]", "Orbital angle [rad]", "Orbital speed [rad/s]",
    "Spin speed [rad/s]",
)
(D_QI, D_QO, D_AI, D_AO, D_SRRI, D_SRRO, D_VSI, D_VSO, D_QE, D_BBX, D_BBY, D_BBZ, D_BBN, D_BBT, D_GAP, D_H, D_PHASE,
 D_PSI, D_PSIDOT, D_SPIN) = range(20)
N_DIAG = 20
RING_DIAG_NAMES = ("Ring force from balls x [N]", "Ring force from balls y [N]", "Ring force from balls z [N]",
                   "Ring torque from balls [N m]", "Rotor friction torque [N m]")
N_RING_DIAG = 5
