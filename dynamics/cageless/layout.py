"""The cage-less bearing's state layout, option codes, the record of its parameters (read by name) and diagnostics.

Part of :mod:`lubedyn.dynamics.cageless` (the package docstring gives the overview)."""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

from .. import contacts as C
from ..groups import record_row

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

# the bearing's parameters: one named field each, the record of PARAMETER_DTYPE the kernels read by name
# (P.ki); the integer options first (int64), then the floats
OPTIONS = (
    ("z", "number of balls Z"), ("dof", "degrees of freedom (DOFS)"), ("film", "ball-ball film kind (FILM_KINDS)"),
    ("drive", "the scenario (SCENARIOS): 0 ring speed held, 1 ring driven by the rotor's friction, 2 free"),
    ("traction", "race traction (TRACTIONS)"), ("ballball", "1: ball-ball contacts on"),
)
PARAMETERS = (
    ("d", "ball diameter D [m]"), ("rb", "ball radius [m]"), ("roc", "outer groove centre radius [m]"),
    ("ric", "inner groove centre radius [m]"), ("ro", "outer groove radius [m]"), ("ri", "inner groove radius [m]"),
    ("mb", "ball mass [kg]"), ("jb", "ball moment of inertia [kg m^2]"), ("mr", "ring mass [kg]"),
    ("jr", "ring moment of inertia [kg m^2]"), ("jrot", "rotor moment of inertia [kg m^2] (0: none)"),
    ("ki", "inner race Hertz constant [N/m^1.5]"), ("ko", "outer race Hertz constant [N/m^1.5]"),
    ("alpha", "race contact damping [s/m]"), ("mu", "traction limit [-]"), ("srr", "traction's slide-to-roll scale [-]"),
    ("vreg", "traction slip regularisation [m/s]"), ("fx", "ring load x [N]"), ("fy", "ring load y [N]"),
    ("fz", "ring load z [N]"), ("g", "gravity [m/s^2]"),
    ("murot", "rotor friction coefficient"), ("rc", "rotor contact radius [m]"),
    ("wreg", "rotor slip regularisation [rad/s]"), ("nrot", "rotor normal load [N]"), ("sw", "slot width [m]"),
    ("sl", "slot length [m]"), ("sblend", "slot blend width [m]"), ("keo", "outer slot edge Hertz constant"),
    ("kei", "inner slot edge Hertz constant"), ("reo", "outer slot edge circle radius [m]"),
    ("rei", "inner slot edge circle radius [m]"), ("qstab", "quaternion drift stabilisation [1/s]"),
    ("hci", "inner race film coefficient [m (s/m)^0.67]"), ("hco", "outer race film coefficient [m (s/m)^0.67]"),
)
PARAMETER_DTYPE = np.dtype([(name, np.int64) for name, _ in OPTIONS] + [(name, np.float64) for name, _ in PARAMETERS], align=True)


def parameter_record(values: dict) -> np.recarray:
    """The kernels' parameter record (:data:`PARAMETER_DTYPE`, read by name: ``P.ki``) from ``values``
    {field: number}, as a record array of one row (the kernels read its row, ``P = args.P[0]``: numba
    takes an array from Python at the cost of any array, a record scalar costs ten times more): every field of :data:`OPTIONS` and :data:`PARAMETERS` and no other, else a
    :class:`DynamicsInputError` naming the field."""
    return record_row(PARAMETER_DTYPE, values, "the cage-less bearing's parameter record", dict(OPTIONS + PARAMETERS), "lubedyn.dynamics.cageless.layout.OPTIONS and PARAMETERS")


class MapArrays(NamedTuple):
    """A ball-ball force map as the kernels read it (:mod:`lubedyn.dynamics.interp`): three prepared axes
    (a two-axis map gets a constant third), the values ((8, n0, n1, n2) Hermite data or (n0, n1, n2)) and the
    reader's options (``lubedyn.dynamics.contacts.MO_*``) as a tuple of :class:`lubedyn.dynamics.interp.Fixed`:
    the axis scales, method, mode and speed-axis kind are compile-time constants of the kernels that read
    this map (one compiled version per combination)."""

    ax0: np.ndarray
    ax1: np.ndarray
    ax2: np.ndarray
    values: np.ndarray
    opts: np.ndarray


class TractionMaps(NamedTuple):
    """The inner and outer race EHL maps' traction coefficient (index 0 inner, 1 outer): axes (2, n_k),
    values (2, k, n0, n1, n2) and the reader's options (a tuple of :class:`lubedyn.dynamics.interp.Fixed`, as
    :class:`MapArrays`)."""

    ax0: np.ndarray
    ax1: np.ndarray
    ax2: np.ndarray
    values: np.ndarray
    opts: np.ndarray


class BallBallMap(NamedTuple):
    """A ball-ball force map's kernel arrays (:class:`lubedyn.maps.KernelArrays`: axes, logs, values, logv,
    method) with the speed axis they are on (a key of :data:`MAP_SPEED_AXES`), as
    :meth:`lubedyn.maps.FilmMap.dynamics_film_map` gives a polar map: ``films.map_speed_axis``, when given,
    must agree with it."""

    arrays: tuple
    speed_axis: str


class KernelArgs(NamedTuple):
    """The arguments of :func:`lubedyn.dynamics.cageless.kernels.rhs`: the parameter record ``P``
    (:func:`parameter_record`), the ball-ball law's parameter record ``bbp`` (one row:
    :func:`lubedyn.lubrication.laws.collision.ball_ball_row` of
    :func:`lubedyn.lubrication.laws.collision.ball_ball_parameters`, read by name), the slots (k, 2: azimuth, race),
    the ball-ball film map (:class:`MapArrays`, None without one), the counter of queries clamped to a
    map's axes and the traction maps (:class:`TractionMaps`, None without them).  None prunes a map's
    readers by type: a model without maps never compiles them."""

    P: np.recarray
    bbp: np.recarray
    slots: np.ndarray
    film_map: MapArrays | None
    counter: np.ndarray
    traction_maps: TractionMaps | None

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
