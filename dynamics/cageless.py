r"""Cage-less deep-groove ball bearing (paper B: 6206 size, 14 balls, local
functional slots, balls colliding through the oil film), as a numba
right-hand side.

Frames and bodies
-----------------
Inertial frame: x horizontal, y up (gravity -g e_y), z the bearing axis.  The
outer ring is fixed with its centre at the origin.  The inner ring (carrying
the rotor's mass) translates freely (x, y; and z with the 6-DOF balls) and
turns about z (angle theta, speed omega); the rotor turns at Omega.  Ball j
has centre c_j, velocity v_j and angular velocity w_j.

Degrees of freedom (option ``dof``)
    ``"6dof"``: per ball position (3), unit quaternion (4, scalar first, body
    -> inertial, :mod:`dynamics.rotations`), velocity (3) and body-frame
    angular velocity (3) with Euler's equations (the gyroscopic term
    w x J w vanishes for a sphere but is kept general).  13 states/ball.
    ``"planar"``: the ball stays in the mid-plane z = 0: orbital angle phi,
    radial position r, spin angle and spin speed about the axis-parallel
    direction, (phi, r, theta_b, dphi/dt, dr/dt, omega_b), with
    m (r'' - r phi'^2) = F_r, m (r phi'' + 2 r' phi') = F_t, J omega_b' = T_z.
    6 states/ball.  No axial load (it needs a contact angle).

State vector (:meth:`CagelessBearing.state_layout` names every entry)::

    [ring x, y, z, theta, vx, vy, vz, omega, rotor Omega] (9)
    [delta_max of ball pair j, j+1 (mod Z)]               (Z: plastic memory)
    [ball 0 block, ball 1 block, ...]                      (Z x 13 or Z x 6)

Ball-race contact (rigid rings, groove curvature centres)
--------------------------------------------------------
The groove of a race is a torus; its curvature centre circle has radius
R_oc = D_o/2 - r_o (outer, about the origin) and R_ic = D_i/2 + r_i (inner,
about the inner-ring centre c_i, axial offset z_i).  For a ball at radial
distance rho from the race axis in its own radial plane (unit e_r), with u =
c - (race centre + R_gc e_r) and L = |u|::

    delta = L - (r_g - D/2),   n = u/L,   Q = K delta^1.5 (1 + alpha d(delta)/dt)  (Hunt-Crossley)

the force on the ball is -Q n at the contact point p = c + (D/2) n (the
reaction +Q n acts on the inner ring); the contact angle reported is the
angle of the load line, atan(n_z/n_r) at the outer race and atan(-n_z/n_r)
at the inner race (equal for a ball loaded only by the two races).
K is the exact Hertz constant of :mod:`dynamics.contacts` at the zero-angle
curvature (its change with the angle through gamma is < 0.1 %).  Traction:
the closed-form curve mu(SRR) of :func:`lubrication.laws.traction.traction_coefficient`
against the tangential sliding velocity v_s = (v + w x (D/2) n) - v_race(p);
entrainment u_e = |((v_ball + v_race)/2 - v_p)_t| with v_p the velocity of the
contact point (it moves with the ball's orbit).  Spin and rolling-resistance
moments are not modelled.

Functional slots (paper B, Table 4: width W = 3.5 mm across the groove,
length L_s = 11.5 mm along it, depth 1 mm; EDM-cut in the raceway)
    The groove surface is missing where the contact point lies within
    |s| < L_s/2 (arc length along the race from the slot centre) and |z_p| <
    W/2 (axial, from the groove centre plane): the groove force is multiplied
    by 1 - w_s(s) w_z(z_p) (smooth steps of width ``slot_blend``).  Over the
    slot a ball that has lost its groove support drops onto the slot's two
    edges (circles at z = +-W/2 on the groove surface; a sphere against an
    edge rounded with ``slot_edge_radius``, Hertz, weighted by w_s).  A ball
    of D = 9.525 mm dips R - sqrt(R^2 - W^2/4) = 0.33 mm into a 3.5 mm slot,
    less than its 1 mm depth, so the slot floor is never reached (checked).
    Default: one slot in the outer (fixed) ring at the bottom of the load
    zone (azimuth 270 deg, under the radial load), as the paper's figure 3
    discussion places it ("the bearing area has the lowest set of functional
    slots"); count, azimuths and race are options (an inner-ring slot turns
    with theta).

Ball-ball contact between neighbours j, j+1 (no cage; the train keeps its
order since Z D < pi d_m): the film + Hertz series law with collision phases
and film-rupture friction of :func:`dynamics.contacts.ball_ball_normal`.

Inner ring and rotor (option ``scenario``)
    ``"steady"``: omega fixed (driven inner ring), Omega unused.
    ``"drop"``: the rotor, spinning at Omega_0, has landed on the inner ring
    (at rest with the balls, in the quasi-static equilibrium under F_r, F_a)
    and drags it by friction at the rotor-inner ring contact::

        T_f = mu_r F_r r_c tanh((Omega - omega)/omega_reg)
        J_ring omega' = T_balls + T_f,   J_rotor Omega' = -T_f   (J_rotor = inf: driven rotor)

    (a regularised Coulomb law; F_r the normal load in the rotor-ring
    contact, r_c the bore radius).  An initial downward ring speed
    ``drop_speed`` models the impact.
    ``"free"``: omega free, no rotor (T_f = 0).

The inner-ring assembly (ring + rotor, mass ``ring_mass``) carries the radial
load F_r downward (-y) including its own weight, i.e. the applied force is
F_r - m g plus gravity m g, and the axial load F_a along +z.  Gravity also acts
on the balls.

API
---
:class:`CagelessBearing` (parameters, ``args()`` the numba tuple,
``initial_state()`` the quasi-static start, ``state_layout()``/``state_names()``,
``omega_max()`` for the explicit step limit); :func:`rhs` (integrator
contract ``rhs(t, y, args, dydt)``); :func:`forces` / :func:`forces_many`
(contact loads, angles, slip, ball-ball force vectors, film thickness and
collision phase at sampled states, columns :data:`DIAG_NAMES`);
:func:`bearing_energy`, :func:`angular_momentum_z` (invariants for checks).

Speed
-----
The contact kernels take and return scalars and are inlined (numba
``inline='always'``), ball kinematics and the quaternion algebra are written
out on scalars (no array views in the ball loops: each costs an atomic
reference-count pair), the contact angle is computed only for
:func:`forces`, and points far from a slot are skipped by a dot product
before the atan2.  Measured costs per ``rhs`` call are in
``benchmarks/README.md`` ("Cost of the bearing right-hand side").
A model without a film map or traction maps passes None in their places of
:meth:`CagelessBearing.args`, so numba prunes the map readers by type: the
rhs call at the start of the drop then takes 2.46 us against 4.42 us with
the unused readers compiled in (same process, fastest of 300 x 100 calls;
the 5 ms drop with DOPRI5 0.099 s against 0.203 s, identical steps and
states), and the cold compile of the main job's kernels falls by ~40 % CPU.
Largest stable RK4 step at 10,000 rpm (F_r 2000 N, F_a 200 N, slot): 1.33e-5
s steady, 1.25e-5 s during the rotor drop with ball collisions;
:meth:`CagelessBearing.omega_max` gives 2.83/omega_max = 1.03e-5 s
(conservative by ~25 %).
"""
from __future__ import annotations

import logging
import math
from dataclasses import dataclass, fields

import numpy as np
from numba import njit

from lubrication.errors import did_you_mean
from lubrication.laws import bearing as laws_bearing
from lubrication.laws import contact as laws_contact
from lubrication.laws.collision import BB_HCUT, BB_K, BB_VREG, ball_ball_parameters, hertz_force
from lubrication.laws.film import hamrock_dowson_central
from lubrication.laws.jit import INLINE, JIT
from lubrication.laws.traction import traction_coefficient

from . import contacts as C
from .contacts import FILM_KINDS, FILM_NONE, ball_ball_friction_coefficient, ball_ball_normal, plastic_memory_rate
from .errors import DynamicsInputError
from .interp import HERMITE, hermite3, interp3

logger = logging.getLogger(__name__)

DOFS = {"planar": 0, "6dof": 1}
SCENARIOS = {"steady": 0, "drop": 1, "free": 2}
RACES = {"outer": 0, "inner": 1}
TRACTIONS = {"closed_form": 0, "map": 1}
RACE_FILMS = {"none": 0, "closed_form": 1}
MAP_SPEED_AXES = {"approach_speed": C.MAP_AXIS_APPROACH, "squeeze_number": C.MAP_AXIS_SQUEEZE,
                  "polar": C.MAP_AXIS_POLAR}
# traction maps start at a slide-to-roll ratio > 0 (coupling.film_points, "Traction axis"): below the
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


# ----------------------------------------------------------------------------- kernels
@njit(**JIT)
def _traction_from_map(tmap, race, Q, ue, vs, counter):
    """Traction coefficient of the EHL map of ``race`` (load, entrainment speed, slide-to-roll ratio).

    Below the map's first slide-to-roll node the coefficient is linear in the SRR
    (coupling.film_points, "Traction axis").  ``tmap`` is None in a model without
    traction maps: numba prunes the ``is None`` branch by type, so such a model never
    compiles the map readers (about a third of the cold compile of ``rhs``)."""
    if tmap is None:
        return math.nan
    ax0, ax1, ax2, vals, opts = tmap
    sq = vs / ue
    s_lo = math.exp(ax2[race][0]) if opts[C.MO_LOG2] == 1 else ax2[race][0]
    lin = 1.0
    if sq < s_lo:
        lin, sq = sq / s_lo, s_lo * (1.0 + 1e-12)
    if opts[C.MO_METHOD] == HERMITE:
        mu = hermite3(ax0[race], ax1[race], ax2[race], opts[C.MO_LOG0], opts[C.MO_LOG1], opts[C.MO_LOG2],
                      vals[race], opts[C.MO_LOGV], Q, ue, sq, opts[C.MO_MODE], counter)
    else:
        mu = interp3(ax0[race], ax1[race], ax2[race], opts[C.MO_LOG0], opts[C.MO_LOG1], opts[C.MO_LOG2],
                     vals[race][0], opts[C.MO_LOGV], opts[C.MO_METHOD], Q, ue, sq, opts[C.MO_MODE], counter)
    return lin * abs(mu)


@njit(**INLINE)
def _race_contact(c0, c1, v0, v1, v2, w0, w1, w2, n0, n1, n2, delta, K, ctr0, ctr1, vc0, vc1, vc2, wr, inner, Rb,
                  alpha, mu_lim, srr_ref, v_reg, hc_coef, tmap, race, counter, want):
    """One ball-race (or slot-edge) contact of a ball (centre c, velocity v,
    angular velocity w, inertial frame) with normal n (ball force -Q n,
    contact point c + (D/2) n) on a race with centre ``ctr``, centre
    velocity ``vc`` and speed ``wr``.  Returns (Q, SRR, sliding speed,
    contact angle (only with ``want``, else 0), force on the ball (3),
    torque on the ball (3), z-moment p x f of that force about the race
    centre); an ``inner`` race takes -force and -moment.

    ``hc_coef`` > 0: an EHL film of central thickness h_c = hc_coef u_e^0.67
    (Hamrock-Dowson at a reference load, :meth:`CagelessBearing.race_film_thickness`)
    separates the surfaces, so the solids' approach is delta + h_c.

    ``race`` >= 0 with a traction map (``tmap``, :func:`_traction_arrays`): the
    traction coefficient is read from the EHL map of that race over (load,
    entrainment speed, |slide-to-roll ratio|) instead of the closed form;
    queries outside its axes are clamped and counted in ``counter[0]``.
    ``race`` = -1 (slot edges, or no map): the closed-form curve.

    Scalars in, scalars out, inlined (numba ``inline='always'``) into the
    rhs: an array passed to or viewed in a loop body costs an atomic
    reference-count pair, and those were about a third of the rhs time."""
    vx, vy, vz = v0 - vc0, v1 - vc1, v2 - vc2
    ddot = n0 * vx + n1 * vy + n2 * vz
    angle = 0.0
    # contact angle of the load line, positive when the ball is pushed towards -z at this contact
    if want:
        angle = math.atan2(n2 if not inner else -n2, math.sqrt(n0 * n0 + n1 * n1))
    if hc_coef <= 0.0 and delta <= 0.0:
        return 0.0, 0.0, 0.0, angle, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    # contact point relative to the ball centre and to the race centre
    a0, a1, a2 = Rb * n0, Rb * n1, Rb * n2
    p0, p1 = c0 + a0 - ctr0, c1 + a1 - ctr1
    # surface velocities at the contact point
    vb0 = v0 + w1 * a2 - w2 * a1
    vb1 = v1 + w2 * a0 - w0 * a2
    vb2 = v2 + w0 * a1 - w1 * a0
    vr0, vr1, vr2 = vc0 - wr * p1, vc1 + wr * p0, vc2
    # orbital rate of the ball about the race axis -> contact point velocity
    d0, d1 = c0 - ctr0, c1 - ctr1
    rho2 = d0 * d0 + d1 * d1
    psid = (d0 * vy - d1 * vx) / rho2 if rho2 > 0.0 else 0.0
    vp0, vp1, vp2 = vc0 - psid * p1, vc1 + psid * p0, vc2
    s0, s1, s2 = vb0 - vr0, vb1 - vr1, vb2 - vr2
    sn = s0 * n0 + s1 * n1 + s2 * n2
    s0 -= sn * n0
    s1 -= sn * n1
    s2 -= sn * n2
    e0 = 0.5 * (vb0 + vr0) - vp0
    e1 = 0.5 * (vb1 + vr1) - vp1
    e2 = 0.5 * (vb2 + vr2) - vp2
    en = e0 * n0 + e1 * n1 + e2 * n2
    e0 -= en * n0
    e1 -= en * n1
    e2 -= en * n2
    ue = math.sqrt(e0 * e0 + e1 * e1 + e2 * e2)
    if hc_coef > 0.0:
        delta += hc_coef * ue**0.67
    Q = hertz_force(delta, ddot, K, alpha)
    if Q <= 0.0:
        return Q, 0.0, 0.0, angle, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    vs = math.sqrt(s0 * s0 + s1 * s1 + s2 * s2)
    srr = vs / ue if ue > 0.0 else 0.0
    ft0 = 0.0
    ft1 = 0.0
    ft2 = 0.0
    if vs > 0.0:
        if race >= 0 and ue > 0.0:
            mu = _traction_from_map(tmap, race, Q, ue, vs, counter)
        else:
            mu = traction_coefficient(vs, ue, mu_lim, srr_ref, v_reg)
        f = -mu * Q / vs
        ft0, ft1, ft2 = f * s0, f * s1, f * s2
    fx, fy, fz = -Q * n0 + ft0, -Q * n1 + ft1, -Q * n2 + ft2
    return (Q, srr, vs, angle, fx, fy, fz, a1 * ft2 - a2 * ft1, a2 * ft0 - a0 * ft2, a0 * ft1 - a1 * ft0,
            p0 * fy - p1 * fx)


@njit(**INLINE)
def _smooth_in(x, half, blend):
    """~1 for |x| < half, ~0 beyond, over a width ``blend``."""
    return 0.5 * (1.0 - math.tanh((abs(x) - half) / blend))


@njit(**INLINE)
def _slot_weight(px, py, pz, race, ring_theta, slots, R_race, P, sdir, cfar):
    """Largest slot weight w_s(s) w_z(z) of a point (relative to the race centre)
    and the largest arc weight w_s alone.  Exactly 0 farther than 10 blend widths
    beyond a slot's end (where the smooth step is below 1e-8).

    ``sdir[k] = (cos, sin)`` of slot k's azimuth (with the ring angle for an
    inner-ring slot) and ``cfar`` the cosine of 1.01 times the angular reach
    far/R_race (-2 when that reaches past pi): a point whose direction is
    farther from the slot than that is skipped with a dot product, before
    the atan2 (the same points the arc-length test skips; results unchanged)."""
    best = 0.0
    best_s = 0.0
    far = 0.5 * P[P_SL] + 10.0 * P[P_SBLEND]
    psi = 0.0
    have_psi = False
    rho_p = -1.0
    for k in range(slots.shape[0]):
        if int(slots[k, 1]) != race:
            continue
        if rho_p < 0.0:
            rho_p = math.sqrt(px * px + py * py)
        if px * sdir[k, 0] + py * sdir[k, 1] < cfar * rho_p:
            continue
        if not have_psi:
            psi = math.atan2(py, px)
            have_psi = True
        az = slots[k, 0] + (ring_theta if race == 1 else 0.0)
        dpsi = (psi - az + math.pi) % (2.0 * math.pi) - math.pi
        s_arc = R_race * dpsi
        if abs(s_arc) > far:
            continue
        ws = _smooth_in(s_arc, 0.5 * P[P_SL], P[P_SBLEND])
        if ws > best_s:
            best_s = ws
        wz = _smooth_in(pz, 0.5 * P[P_SW], P[P_SBLEND])
        if ws * wz > best:
            best = ws * wz
    return best, best_s


@njit(**INLINE)
def _slot_directions(P, slots, ring_theta, sdir, cfar):
    """sdir[k] <- (cos, sin) of slot k's azimuth (plus the ring angle for an
    inner-ring slot); cfar[race] <- cos of 1.01 times the angular reach
    far/R_race of a slot's weight on that race (-2 when it reaches past pi),
    for the dot-product skip of :func:`_slot_weight`."""
    far = 0.5 * P[P_SL] + 10.0 * P[P_SBLEND]
    for race in range(2):
        R_race = P[P_RO] + P[P_ROC] if race == 0 else P[P_RIC] - P[P_RI]
        reach = 1.01 * far / R_race
        cfar[race] = math.cos(reach) if reach < math.pi else -2.0
    for k in range(slots.shape[0]):
        az = slots[k, 0] + (ring_theta if int(slots[k, 1]) == 1 else 0.0)
        sdir[k, 0] = math.cos(az)
        sdir[k, 1] = math.sin(az)


@njit(**INLINE)
def _ball_races(j, cpos, cvel, cw, y, P, slots, diag, tmap, use_map, counter, want, sdir, cfar):
    """Both race contacts (and slot edges) of ball j: returns the force and
    torque on the ball (6) and the force and z-torque on the inner ring (4);
    with ``want`` its diagnostics go to diag[j] (race loads, angles, slip,
    slot-edge load)."""
    D = P[P_D]
    Rb = P[P_RB]
    halfw = 0.5 * P[P_SW]
    c0, c1, c2 = cpos[j, 0], cpos[j, 1], cpos[j, 2]
    v0, v1, v2 = cvel[j, 0], cvel[j, 1], cvel[j, 2]
    w0, w1, w2 = cw[j, 0], cw[j, 1], cw[j, 2]
    alpha, mu_lim, srr_ref, v_reg = P[P_ALPHA], P[P_MU], P[P_SRR], P[P_VREG]
    F0 = F1 = F2 = T0 = T1 = T2 = 0.0
    R0 = R1 = R2 = R3 = 0.0
    if want:
        diag[j, D_QE] = 0.0
    for race in range(2):
        if race == 0:
            Rgc, rg, K, KE, RE = P[P_ROC], P[P_RO], P[P_KO], P[P_KEO], P[P_REO]
            ctr0, ctr1, ctr2 = 0.0, 0.0, 0.0
            vc0, vc1, vc2 = 0.0, 0.0, 0.0
            wr = 0.0
            th = 0.0
        else:
            Rgc, rg, K, KE, RE = P[P_RIC], P[P_RI], P[P_KI], P[P_KEI], P[P_REI]
            ctr0, ctr1, ctr2 = y[0], y[1], y[2]
            vc0, vc1, vc2 = y[4], y[5], y[6]
            wr = y[7]
            th = y[3]
        d0, d1, d2 = c0 - ctr0, c1 - ctr1, c2 - ctr2
        rho = math.sqrt(d0 * d0 + d1 * d1)
        er0, er1 = d0 / rho, d1 / rho
        ur = rho - Rgc
        L = math.sqrt(ur * ur + d2 * d2)
        n0, n1, n2 = ur / L * er0, ur / L * er1, d2 / L
        delta = L - (rg - 0.5 * D)
        wslot = 0.0
        wsarc = 0.0
        if slots.shape[0] > 0:
            wslot, wsarc = _slot_weight(d0 + Rb * n0, d1 + Rb * n1, d2 + Rb * n2, race, th, slots,
                                        rg + Rgc if race == 0 else Rgc - rg, P, sdir, cfar[race])
        Q, srr, vs, ang, fx, fy, fz, tx, ty, tz, mz = _race_contact(
            c0, c1, v0, v1, v2, w0, w1, w2, n0, n1, n2, delta, K * (1.0 - wslot), ctr0, ctr1, vc0, vc1, vc2, wr,
            race == 1, Rb, alpha, mu_lim, srr_ref, v_reg, P[P_HCO] if race == 0 else P[P_HCI], tmap,
            race if use_map else -1, counter, want)
        F0 += fx
        F1 += fy
        F2 += fz
        T0 += tx
        T1 += ty
        T2 += tz
        if race == 1:  # the inner ring takes the reaction
            R0 -= fx
            R1 -= fy
            R2 -= fz
            R3 -= mz
        if want:
            if race == 0:
                diag[j, D_QO] = Q
                diag[j, D_AO] = ang
                diag[j, D_SRRO] = srr
                diag[j, D_VSO] = vs
            else:
                diag[j, D_QI] = Q
                diag[j, D_AI] = ang
                diag[j, D_SRRI] = srr
                diag[j, D_VSI] = vs
        if wsarc > 1e-6:  # slot edges: circles at z = +-W/2 on the groove surface
            for sgn in (-1.0, 1.0):
                ez = sgn * halfw
                u_r = rho - RE
                u_z = d2 - ez
                Le = math.sqrt(u_r * u_r + u_z * u_z)
                de = Rb - Le
                if de > 0.0:
                    # normal from the ball centre towards the edge
                    m0, m1, m2 = -u_r / Le * er0, -u_r / Le * er1, -u_z / Le
                    Qe, _, _, _, fx, fy, fz, tx, ty, tz, mz = _race_contact(
                        c0, c1, v0, v1, v2, w0, w1, w2, m0, m1, m2, de, KE * wsarc, ctr0, ctr1, vc0, vc1, vc2, wr,
                        race == 1, Rb, alpha, mu_lim, srr_ref, v_reg, 0.0, tmap, -1, counter, want)
                    F0 += fx
                    F1 += fy
                    F2 += fz
                    T0 += tx
                    T1 += ty
                    T2 += tz
                    if race == 1:
                        R0 -= fx
                        R1 -= fy
                        R2 -= fz
                        R3 -= mz
                    if want:
                        diag[j, D_QE] += Qe
    return F0, F1, F2, T0, T1, T2, R0, R1, R2, R3


@njit(**INLINE)
def _rotate3(w, x, y, z, v0, v1, v2):
    """R(q) v for the unit quaternion (w, x, y, z), scalars (the arithmetic of
    :func:`dynamics.rotations.quat_rotate`; pass (w, -x, -y, -z) for R^T v)."""
    tx = 2.0 * (y * v2 - z * v1)
    ty = 2.0 * (z * v0 - x * v2)
    tz = 2.0 * (x * v1 - y * v0)
    return v0 + w * tx + (y * tz - z * ty), v1 + w * ty + (z * tx - x * tz), v2 + w * tz + (x * ty - y * tx)


@njit(**JIT)
def _evaluate(t, y, args, dydt, diag, ring_diag):
    iopt, P, bbp, slots, map_ax0, map_ax1, map_ax2, map_vals, map_opts, counter, tmap = args
    want = diag.shape[0] > 0
    Z = iopt[I_Z]
    dof = iopt[I_DOF]
    nb = NB_6DOF if dof == 1 else NB_PLANAR
    off = N_RING + Z
    mb = P[P_MB]
    Jb = P[P_JB]
    g = P[P_G]
    Rb = P[P_RB]
    D = P[P_D]
    use_map = iopt[I_TRACTION] == 1
    # Kinematics of every ball in the inertial frame, ball forces and torques in one allocation, the
    # ring load and the slot directions in another; no array views in the loops below (a view costs an
    # atomic reference-count pair, which dominated the cost of this function before).
    bw = np.empty((5, Z, 3))
    cpos = bw[0]
    cvel = bw[1]
    cw = bw[2]
    Fb = bw[3]
    Tb = bw[4]
    nslot = slots.shape[0]
    sw = np.empty(6 + 2 * nslot)
    RF = sw[0:4]  # ring force x, y, z and torque from the balls
    cfar = sw[4:6]
    sdir = sw[6:6 + 2 * nslot].reshape((nslot, 2))
    for k in range(4):
        RF[k] = 0.0
    _slot_directions(P, slots, y[3], sdir, cfar)
    for j in range(Z):
        b = off + j * nb
        for k in range(3):
            Fb[j, k] = 0.0
            Tb[j, k] = 0.0
        if dof == 1:
            for k in range(3):
                cpos[j, k] = y[b + k]
                cvel[j, k] = y[b + 7 + k]
            inv = 1.0 / math.sqrt(y[b + 3] ** 2 + y[b + 4] ** 2 + y[b + 5] ** 2 + y[b + 6] ** 2)
            cw[j, 0], cw[j, 1], cw[j, 2] = _rotate3(y[b + 3] * inv, y[b + 4] * inv, y[b + 5] * inv,
                                                    y[b + 6] * inv, y[b + 10], y[b + 11], y[b + 12])
        else:
            phi, r, phid, rd, om = y[b], y[b + 1], y[b + 3], y[b + 4], y[b + 5]
            cp, sp = math.cos(phi), math.sin(phi)
            cpos[j, 0] = r * cp
            cpos[j, 1] = r * sp
            cpos[j, 2] = 0.0
            cvel[j, 0] = rd * cp - r * phid * sp
            cvel[j, 1] = rd * sp + r * phid * cp
            cvel[j, 2] = 0.0
            cw[j, 0] = 0.0
            cw[j, 1] = 0.0
            cw[j, 2] = om
    for j in range(Z):
        F0, F1, F2, T0, T1, T2, R0, R1, R2, R3 = _ball_races(j, cpos, cvel, cw, y, P, slots, diag, tmap, use_map,
                                                            counter, want, sdir, cfar)
        Fb[j, 0] = F0
        Fb[j, 1] = F1
        Fb[j, 2] = F2
        Tb[j, 0] = T0
        Tb[j, 1] = T1
        Tb[j, 2] = T2
        RF[0] += R0
        RF[1] += R1
        RF[2] += R2
        RF[3] += R3
    # ball-ball pairs j, j+1
    for j in range(Z):
        dydt[N_RING + j] = 0.0
    if iopt[I_BALLBALL] == 1:
        for j in range(Z):
            k = j + 1 if j + 1 < Z else 0
            d0 = cpos[k, 0] - cpos[j, 0]
            d1 = cpos[k, 1] - cpos[j, 1]
            d2 = cpos[k, 2] - cpos[j, 2]
            dist = math.sqrt(d0 * d0 + d1 * d1 + d2 * d2)
            gap = dist - D
            dmax = y[N_RING + j]
            if want:
                diag[j, D_GAP] = gap
                diag[j, D_H] = gap
            if gap > 0.0 and (iopt[I_FILM] == FILM_NONE or gap >= bbp[BB_HCUT]):
                dydt[N_RING + j] = plastic_memory_rate(0.0, 0.0, dmax, 0.0, bbp)
                continue
            n0, n1, n2 = d0 / dist, d1 / dist, d2 / dist
            r0 = cvel[k, 0] - cvel[j, 0]
            r1 = cvel[k, 1] - cvel[j, 1]
            r2 = cvel[k, 2] - cvel[j, 2]
            vapp = -(r0 * n0 + r1 * n1 + r2 * n2)
            a0, a1, a2 = Rb * n0, Rb * n1, Rb * n2
            wj0, wj1, wj2 = cw[j, 0], cw[j, 1], cw[j, 2]
            wk0, wk1, wk2 = cw[k, 0], cw[k, 1], cw[k, 2]
            # entrainment: mean surface velocity at the contact relative to the pair's mean, (w_j - w_k) x a / 2
            e0 = 0.5 * ((wj1 - wk1) * a2 - (wj2 - wk2) * a1)
            e1 = 0.5 * ((wj2 - wk2) * a0 - (wj0 - wk0) * a2)
            e2 = 0.5 * ((wj0 - wk0) * a1 - (wj1 - wk1) * a0)
            ue = math.sqrt(e0 * e0 + e1 * e1 + e2 * e2)
            Fn, h, de, phase, share = ball_ball_normal(gap, vapp, ue, dmax, bbp, iopt[I_FILM], map_ax0, map_ax1,
                                                       map_ax2, map_vals, map_opts, counter)
            dydt[N_RING + j] = plastic_memory_rate(de, share * vapp, dmax, Fn, bbp)
            f0, f1, f2 = Fn * n0, Fn * n1, Fn * n2
            ft = 0.0
            if Fn > 0.0:
                # sliding velocity of k's surface relative to j's at the contact point
                s0 = r0 + (wk1 * -a2 - wk2 * -a1) - (wj1 * a2 - wj2 * a1)
                s1 = r1 + (wk2 * -a0 - wk0 * -a2) - (wj2 * a0 - wj0 * a2)
                s2 = r2 + (wk0 * -a1 - wk1 * -a0) - (wj0 * a1 - wj1 * a0)
                sn = s0 * n0 + s1 * n1 + s2 * n2
                s0 -= sn * n0
                s1 -= sn * n1
                s2 -= sn * n2
                vs = math.sqrt(s0 * s0 + s1 * s1 + s2 * s2)
                if vs > 0.0:
                    mu = ball_ball_friction_coefficient(h, bbp)
                    ft = mu * Fn * math.tanh(vs / bbp[BB_VREG])
                    t0, t1, t2 = -ft * s0 / vs, -ft * s1 / vs, -ft * s2 / vs  # on k
                    f0 += t0
                    f1 += t1
                    f2 += t2
                    # torques: on k at -a, on j (force -t) at +a
                    Tb[k, 0] += -a1 * t2 + a2 * t1
                    Tb[k, 1] += -a2 * t0 + a0 * t2
                    Tb[k, 2] += -a0 * t1 + a1 * t0
                    Tb[j, 0] += a1 * -t2 - a2 * -t1
                    Tb[j, 1] += a2 * -t0 - a0 * -t2
                    Tb[j, 2] += a0 * -t1 - a1 * -t0
            Fb[k, 0] += f0
            Fb[k, 1] += f1
            Fb[k, 2] += f2
            Fb[j, 0] -= f0
            Fb[j, 1] -= f1
            Fb[j, 2] -= f2
            if want:
                diag[j, D_BBX] = f0
                diag[j, D_BBY] = f1
                diag[j, D_BBZ] = f2
                diag[j, D_BBN] = Fn
                diag[j, D_BBT] = ft
                diag[j, D_H] = h
                diag[j, D_PHASE] = phase
    # balls: equations of motion
    stab = P[P_QSTAB]
    for j in range(Z):
        b = off + j * nb
        Fb[j, 1] -= mb * g
        if dof == 1:
            for k in range(3):
                dydt[b + k] = y[b + 7 + k]
                dydt[b + 7 + k] = Fb[j, k] / mb
            # dq/dt = q * (0, w_b) / 2 - k (|q|^2 - 1) q (dynamics.rotations.quat_derivative)
            qw, qx, qy, qz = y[b + 3], y[b + 4], y[b + 5], y[b + 6]
            ox, oy, oz = y[b + 10], y[b + 11], y[b + 12]
            dq0 = 0.5 * (-qx * ox - qy * oy - qz * oz)
            dq1 = 0.5 * (qw * ox + qy * oz - qz * oy)
            dq2 = 0.5 * (qw * oy - qx * oz + qz * ox)
            dq3 = 0.5 * (qw * oz + qx * oy - qy * ox)
            if stab != 0.0:
                cst = stab * (qw * qw + qx * qx + qy * qy + qz * qz - 1.0)
                dq0 -= cst * qw
                dq1 -= cst * qx
                dq2 -= cst * qy
                dq3 -= cst * qz
            dydt[b + 3] = dq0
            dydt[b + 4] = dq1
            dydt[b + 5] = dq2
            dydt[b + 6] = dq3
            # Euler's equations for a sphere (J1 = J2 = J3 = Jb; dynamics.rotations.euler_rate)
            inv = 1.0 / math.sqrt(qw ** 2 + qx ** 2 + qy ** 2 + qz ** 2)
            tb0, tb1, tb2 = _rotate3(qw * inv, -(qx * inv), -(qy * inv), -(qz * inv), Tb[j, 0], Tb[j, 1], Tb[j, 2])
            dydt[b + 10] = (tb0 - (Jb - Jb) * oy * oz) / Jb
            dydt[b + 11] = (tb1 - (Jb - Jb) * oz * ox) / Jb
            dydt[b + 12] = (tb2 - (Jb - Jb) * ox * oy) / Jb
        else:
            phi, r, phid, rd, om = y[b], y[b + 1], y[b + 3], y[b + 4], y[b + 5]
            cp, sp = math.cos(phi), math.sin(phi)
            Fr = Fb[j, 0] * cp + Fb[j, 1] * sp
            Ft = -Fb[j, 0] * sp + Fb[j, 1] * cp
            dydt[b] = phid
            dydt[b + 1] = rd
            dydt[b + 2] = om
            dydt[b + 3] = (Ft / mb - 2.0 * rd * phid) / r
            dydt[b + 4] = r * phid * phid + Fr / mb
            dydt[b + 5] = Tb[j, 2] / Jb
        if want:
            c0, c1 = cpos[j, 0], cpos[j, 1]
            diag[j, D_PSI] = math.atan2(c1, c0)
            diag[j, D_PSIDOT] = (c0 * cvel[j, 1] - c1 * cvel[j, 0]) / (c0 * c0 + c1 * c1)
            diag[j, D_SPIN] = cw[j, 2]
    # inner ring and rotor
    mr = P[P_MR]
    dydt[0] = y[4]
    dydt[1] = y[5]
    dydt[2] = y[6]
    dydt[3] = y[7]
    dydt[4] = (RF[0] + P[P_FX]) / mr
    dydt[5] = (RF[1] + P[P_FY]) / mr - g
    if dof == 1:
        dydt[6] = (RF[2] + P[P_FZ]) / mr
    else:
        dydt[2] = 0.0
        dydt[6] = 0.0
    drive = iopt[I_DRIVE]
    Tf = 0.0
    if drive == 0:
        dydt[7] = 0.0
        dydt[8] = 0.0
    elif drive == 1:
        Tf = P[P_MUROT] * P[P_NROT] * P[P_RC] * math.tanh((y[8] - y[7]) / P[P_WREG])
        dydt[7] = (RF[3] + Tf) / P[P_JR]
        dydt[8] = -Tf / P[P_JROT] if P[P_JROT] > 0.0 else 0.0
    else:
        dydt[7] = RF[3] / P[P_JR]
        dydt[8] = 0.0
    if want:
        ring_diag[0] = RF[0]
        ring_diag[1] = RF[1]
        ring_diag[2] = RF[2]
        ring_diag[3] = RF[3]
        ring_diag[4] = Tf


@njit(**JIT)
def rhs(t, y, args, dydt):
    """Right-hand side ``dy/dt`` of the cage-less bearing (integrator contract)."""
    _evaluate(t, y, args, dydt, np.empty((0, 0)), np.empty(0))


@njit(**JIT)
def rhs_scaled(t, z, args, dzdt):
    """``rhs`` of the scaled state z = y / scale, ``args = (model args, scale)``.

    Lyapunov exponents do not change under a constant scaling of the state,
    but finite-difference tangent dynamics do: the state mixes metres
    (contact deflections of micrometres) with rad/s (thousands), and one
    perturbation size cannot suit both.  On z every entry has its natural
    perturbation scale (:meth:`CagelessBearing.state_scales`)."""
    inner, scale = args[0], args[1]
    y = z * scale
    rhs(t, y, inner, dzdt)
    for i in range(z.size):
        dzdt[i] /= scale[i]


@njit(**JIT)
def forces(t, y, args):
    """Contact forces at a state: ``(diag (Z, N_DIAG), ring_diag (N_RING_DIAG,), dydt)``.

    Columns of ``diag`` are named by :data:`DIAG_NAMES`; the ball-ball columns
    of row j belong to the pair (j, j+1 mod Z) and give the force on ball j+1."""
    Z = args[0][I_Z]
    dydt = np.empty(y.size)
    diag = np.zeros((Z, N_DIAG))
    ring_diag = np.zeros(N_RING_DIAG)
    _evaluate(t, y, args, dydt, diag, ring_diag)
    return diag, ring_diag, dydt


@njit(**JIT)
def forces_many(t, Y, args):
    """:func:`forces` at every row of ``Y`` (shape (m, n)): ``(diag (m, Z, N_DIAG), ring (m, N_RING_DIAG))``."""
    m = Y.shape[0]
    Z = args[0][I_Z]
    D = np.zeros((m, Z, N_DIAG))
    R = np.zeros((m, N_RING_DIAG))
    for i in range(m):
        d, r, _ = forces(t[i], Y[i], args)
        D[i] = d
        R[i] = r
    return D, R


# ----------------------------------------------------------------------------- model builder
def _check_choice(key, value, allowed):
    if value not in allowed:
        hint = did_you_mean(value, allowed, n=2)
        raise DynamicsInputError(f"{key} = {value!r} is not allowed; choose one of {', '.join(map(repr, allowed))}{hint}")


def _map_arrays(film_map, axis1_kind):
    """(ax0, ax1, ax2, vals (k, n0, n1, n2), opts) for the map kernel from a force map's kernel arrays
    ``(axes, logs, values, logv, method)`` (:class:`coupling.maps.KernelArrays`); a two-axis map (gap,
    speed) gets a constant third axis."""
    from .interp import HERMITE

    if len(film_map) == 6:  # (axes, logs, values, logv, method, axis kind name): coupling.maps.FilmMap.dynamics_film_map
        axis1_kind = MAP_SPEED_AXES[film_map[5]]
        film_map = tuple(film_map[:5])
    try:
        axes, logs, values, logv, method = film_map
    except (TypeError, ValueError):
        raise DynamicsInputError("film_map must be (axes, logs, values, logv, method) of a force map "
                                 "(coupling.maps.FilmMap.kernel_arrays('Force [N]'))") from None
    axes = [np.ascontiguousarray(a, dtype=np.float64) for a in axes]
    logs = [int(v) for v in logs]
    vals = np.asarray(values, dtype=np.float64)
    nd = len(axes)
    if nd not in (2, 3) or len(logs) != nd:
        raise DynamicsInputError(f"film_map has {nd} axes; the ball-ball force map needs 2 (gap, speed) or 3 "
                                 "(gap, speed, entrainment speed)")
    shape = tuple(a.size for a in axes)
    hermite = int(method) == HERMITE
    expect = ((2**nd,) if hermite else ()) + shape
    if vals.shape != expect:
        raise DynamicsInputError(f"film_map values have shape {vals.shape}; the axes need {expect}")
    if nd == 2:
        axes.append(np.array([0.0, 1.0]))
        logs.append(0)
        if hermite:  # bit 2 (derivative along the constant axis) is zero
            v3 = np.zeros((8,) + shape + (2,))
            v3[:4] = vals[..., None]
        else:
            v3 = np.repeat(vals[..., None], 2, axis=-1)[None]
        vals = v3
    elif not hermite:
        vals = vals[None]
    opts = np.zeros(C.MO_SIZE, dtype=np.int64)
    opts[C.MO_LOG0], opts[C.MO_LOG1], opts[C.MO_LOG2] = logs
    opts[C.MO_LOGV], opts[C.MO_METHOD], opts[C.MO_MODE] = int(logv), int(method), 0
    opts[C.MO_AXIS1] = axis1_kind
    return axes[0], axes[1], axes[2], np.ascontiguousarray(vals), opts



def _traction_arrays(maps):
    """``(ax0 (2, n0), ax1 (2, n1), ax2 (2, n2), vals (2, k, n0, n1, n2), opts)`` from the kernel arrays
    (:class:`coupling.maps.KernelArrays` of "Traction coefficient [-]") of the inner and the outer race
    EHL maps, both over (load [N], entrainment speed [m/s], slide-to-roll ratio [-]) with the same
    node counts and method."""
    from .interp import HERMITE

    try:
        (ai, li, vi, lvi, mi), (ao, lo, vo, lvo, mo) = maps
    except (TypeError, ValueError):
        raise DynamicsInputError("traction_maps must be (inner, outer) kernel arrays of EHL maps "
                                 "(coupling.maps.FilmMap.kernel_arrays('Traction coefficient [-]'))") from None
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
    return axes[0], axes[1], axes[2], np.ascontiguousarray(np.stack(vals)), opts


@dataclass(frozen=True, kw_only=True)
class CagelessBearing:
    """Cage-less deep-groove ball bearing (SI units).

    The bearing's data (geometry, materials, masses, loads, speed, oil, slots) have no defaults:
    paper B's come from its parameter set, ``coupling.parameters.zhang2024.cageless_bearing()``
    (Tables 1, 2, 4 and the values it had to assume); the defaults left are model options and
    numerical settings.

    Geometry: ``n_balls`` Z, ``ball_diameter`` D, ``pitch_diameter`` d_m,
    groove radii r_i, r_o (groove bottoms at d_m/2 -+ D/2 - P_d/4, P_d the
    ``diametral_clearance``).  Materials: E, nu of the balls and the rings.
    ``ball_mass`` None: from ``ball_density``.  ``ring_mass``: inner ring plus
    the rotor share it carries; ``ring_inertia`` the inner ring alone about its
    axis; ``rotor_inertia`` (inf: driven rotor).  Slots: ``slot_azimuths_deg``
    (empty: none) on ``slot_race``, each ``slot_width`` x ``slot_length`` x
    ``slot_depth``.
    Options: ``dof`` ("6dof", "planar"), ``film`` ("none", "closed_form",
    "map" with ``film_map``), ``scenario`` ("steady", "drop", "free"),
    ``traction`` ("closed_form"; "map" is a reserved slot), ``hertz_method``
    ("exact", "hamrock_brewe"), ``ball_ball`` (contacts between neighbours).
    ``shoulder_contact_angle_deg``: the largest contact angle before the contact
    ellipse runs over the groove shoulder (the paper gives no shoulder
    diameters; 40 deg assumed): a load that needs more is refused.
    """

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
    radial_load: float
    axial_load: float
    gravity: float = 9.81
    speed_rpm: float
    scenario: str = "steady"
    drop_speed: float = 0.0
    rotor_friction: float = 0.1
    rotor_contact_radius: float = 15e-3
    rotor_slip_regularisation: float = 1.0
    dof: str = "6dof"
    hertz_method: str = "exact"
    race_damping: float = 0.2
    race_film: str = "none"
    traction: str = "closed_form"
    traction_maps: tuple | None = None
    traction_limit: float = 0.07
    traction_srr: float = 0.02
    traction_slip_regularisation: float = 0.05
    ball_ball: bool = True
    film: str = "closed_form"
    film_map: tuple | None = None
    film_map_speed_axis: str = "squeeze_number"
    pressure_viscosity: float
    viscosity: float
    film_rupture_thickness: float = 1e-7
    film_cutoff_gap: float | None = None
    yield_stress: float | None = 1.7e9
    ball_ball_damping: float = 0.0
    ball_ball_mu_film: float = 0.03
    ball_ball_mu_boundary: float = 0.1
    ball_ball_slip_regularisation: float = 0.01
    plastic_memory_time: float = 1e-4
    slot_azimuths_deg: tuple
    slot_race: str
    slot_width: float
    slot_length: float
    slot_depth: float
    slot_edge_radius: float = 2e-4
    slot_blend: float = 2e-4
    quaternion_stabilisation: float = 10.0
    shoulder_contact_angle_deg: float = 40.0
    first_ball_azimuth_deg: float = 270.0

    def __post_init__(self):
        _check_choice("dof", self.dof, DOFS)
        _check_choice("race_film", self.race_film, RACE_FILMS)
        _check_choice("scenario", self.scenario, SCENARIOS)
        _check_choice("film", self.film, FILM_KINDS)
        _check_choice("traction", self.traction, TRACTIONS)
        _check_choice("hertz_method", self.hertz_method, laws_contact.METHODS)
        _check_choice("slot_race", self.slot_race, RACES)
        Z = self.n_balls
        if int(Z) != Z or Z < 3:
            raise DynamicsInputError(f"n_balls = {Z!r} must be an integer >= 3")
        for key in ("ball_diameter", "pitch_diameter", "ball_modulus", "ring_modulus", "ball_density", "ring_mass",
                    "ring_inertia", "rotor_inertia", "slot_width", "slot_length", "slot_depth", "slot_edge_radius",
                    "slot_blend", "rotor_contact_radius", "rotor_slip_regularisation",
                    "traction_srr", "traction_slip_regularisation", "film_rupture_thickness",
                    "ball_ball_slip_regularisation", "plastic_memory_time"):
            v = getattr(self, key)
            if not (isinstance(v, (int, float)) and v > 0.0):
                raise DynamicsInputError(f"{key} = {v!r} must be > 0")
        for key in ("radial_load", "axial_load", "gravity", "race_damping", "traction_limit", "viscosity",
                    "rotor_friction", "ball_ball_damping", "quaternion_stabilisation"):
            v = getattr(self, key)
            if not (isinstance(v, (int, float)) and v >= 0.0 and math.isfinite(v)):
                raise DynamicsInputError(f"{key} = {v!r} must be a finite number >= 0")
        D, dm = self.ball_diameter, self.pitch_diameter
        if Z * D >= math.pi * dm:
            raise DynamicsInputError(
                f"n_balls = {Z} balls of D = {D:g} m do not fit the pitch circle: Z D = {Z * D:g} m >= "
                f"pi d_m = {math.pi * dm:g} m")
        BD = self.inner_groove_radius + self.outer_groove_radius - D
        if not (math.isfinite(self.diametral_clearance) and -0.05 * BD < self.diametral_clearance < 4.0 * BD):
            raise DynamicsInputError(
                f"diametral_clearance = {self.diametral_clearance!r} m must lie in ({-0.05 * BD:g}, {4 * BD:g}) m "
                "(negative: interference, i.e. preload)")
        if not D < dm:
            raise DynamicsInputError(f"ball_diameter = {D:g} m must be < pitch_diameter = {dm:g} m")
        for key in ("inner_groove_radius", "outer_groove_radius"):
            if not getattr(self, key) > 0.5 * D:
                raise DynamicsInputError(f"{key} = {getattr(self, key)!r} m must be > D/2 = {0.5 * D:g} m")
        if self.dof == "planar" and self.axial_load != 0.0:
            raise DynamicsInputError(
                f"axial_load = {self.axial_load:g} N needs dof = '6dof' (planar balls stay in the mid-plane "
                "and carry no axial load); set axial_load = 0 or dof = '6dof'")
        _check_choice("film_map_speed_axis", self.film_map_speed_axis, MAP_SPEED_AXES)
        if self.film == "map" and self.film_map is None:
            raise DynamicsInputError("film = 'map' needs film_map = (axes, logs, values, logv, method) of a "
                                     "ball_ball force map (coupling.maps.FilmMap.kernel_arrays('Force [N]'))")
        if self.traction == "map" and self.traction_maps is None:
            raise DynamicsInputError("traction = 'map' needs traction_maps = (inner, outer) kernel arrays of the "
                                     "EHL race maps (coupling.maps.FilmMap.kernel_arrays('Traction coefficient [-]'))")
        if self.yield_stress is not None and not self.yield_stress > 0.0:
            raise DynamicsInputError(f"yield_stress = {self.yield_stress!r} must be > 0 [Pa] (or None: elastic)")
        if self.slot_width >= 2.0 * min(self.inner_groove_radius, self.outer_groove_radius):
            raise DynamicsInputError(f"slot_width = {self.slot_width:g} m must be < the groove diameter")
        dip = 0.5 * D - math.sqrt(0.25 * D * D - 0.25 * self.slot_width**2) if self.slot_width < D else 0.5 * D
        if self.slot_azimuths_deg and dip >= self.slot_depth:
            raise DynamicsInputError(f"slot_depth = {self.slot_depth:g} m: a ball dips {dip:g} m into a slot of width "
                                     f"{self.slot_width:g} m and would reach the slot floor (not modelled)")

    # derived quantities ------------------------------------------------------
    @property
    def mass(self) -> float:
        """Ball mass [kg]."""
        if self.ball_mass is not None:
            return float(self.ball_mass)
        return self.ball_density * math.pi / 6.0 * self.ball_diameter**3

    @property
    def ball_inertia(self) -> float:
        """2/5 m R^2 [kg m^2]."""
        return 0.4 * self.mass * (0.5 * self.ball_diameter) ** 2

    @property
    def e_star_race(self) -> float:
        return laws_contact.reduced_modulus(self.ball_modulus, self.ball_poisson, self.ring_modulus, self.ring_poisson)

    @property
    def e_star_ball(self) -> float:
        return laws_contact.reduced_modulus(self.ball_modulus, self.ball_poisson, self.ball_modulus, self.ball_poisson)

    def hertz_constants(self) -> tuple[float, float]:
        """(K_i, K_o) [N/m^1.5] of the ball-race contacts (zero contact angle)."""
        D, dm = self.ball_diameter, self.pitch_diameter
        es = self.e_star_race
        Ki = laws_contact.hertz_constant(*laws_bearing.race_radii(D, dm, self.inner_groove_radius, "inner"), es, self.hertz_method)
        Ko = laws_contact.hertz_constant(*laws_bearing.race_radii(D, dm, self.outer_groove_radius, "outer"), es, self.hertz_method)
        return Ki, Ko

    def race_film_reference_load(self) -> float:
        """Reference load [N] of the race films: Stribeck's most loaded ball c F_r / Z, c = 4.37
        (:data:`lubrication.laws.bearing.STRIBECK`), or the axial share F_a / Z when larger; at least 1 N."""
        return max(laws_bearing.STRIBECK["point"] * self.radial_load / self.n_balls, self.axial_load / self.n_balls,
                   1.0)

    def race_film_coefficients(self) -> tuple[float, float]:
        """(c_i, c_o) of the race films h_c = c u_e^0.67 [m with u_e in m/s].

        Hamrock & Dowson (1977) central film of an elliptic contact
        (:func:`lubrication.laws.film.hamrock_dowson_central`),
        U = eta0 u_e / (E' R_x), G = alpha E', W = Q / (E' R_x^2), E' = 2 E*,
        k = a/b from the exact ellipse (m = 1 - (b/a)^2 of
        :func:`lubrication.laws.contact.ellipticity_parameter`), evaluated at
        :meth:`race_film_reference_load` (the film depends on the load only as
        Q^-0.067: a tenfold load changes it by 14 %).  Isothermal, fully
        flooded, smooth surfaces; the film adds h_c to the solids' approach."""
        D, dm = self.ball_diameter, self.pitch_diameter
        e_prime = 2.0 * self.e_star_race
        q = self.race_film_reference_load()
        out = []
        for race, groove in (("inner", self.inner_groove_radius), ("outer", self.outer_groove_radius)):
            rx, ry = laws_bearing.race_radii(D, dm, groove, race)
            k = 1.0 / math.sqrt(1.0 - laws_contact.ellipticity_parameter(ry / rx))
            U1 = self.viscosity / (e_prime * rx)  # U per (m/s)
            G = self.pressure_viscosity * e_prime
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
        return laws_bearing.free_contact_angle(self.ball_diameter, self.inner_groove_radius, self.outer_groove_radius,
                                               self.diametral_clearance)

    @property
    def omega_inner(self) -> float:
        return self.speed_rpm * math.pi / 30.0

    @property
    def n_per_ball(self) -> int:
        return NB_6DOF if self.dof == "6dof" else NB_PLANAR

    @property
    def n_states(self) -> int:
        return N_RING + self.n_balls + self.n_balls * self.n_per_ball

    def ball_offset(self, j: int) -> int:
        """Index of ball j's first state entry."""
        return N_RING + self.n_balls + j * self.n_per_ball

    def cage_speed(self, contact_angle: float = 0.0) -> float:
        """Epicyclic ball-train speed omega_i (1 - D cos a/d_m)/2 [rad/s]."""
        return laws_bearing.cage_speed(self.ball_diameter, self.pitch_diameter, contact_angle, self.omega_inner)

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
        return self.args()[ARG_COUNTER]

    def _build_args(self) -> tuple:
        D, dm = self.ball_diameter, self.pitch_diameter
        Rb = 0.5 * D
        iopt = np.zeros(I_SIZE, dtype=np.int64)
        iopt[I_Z] = self.n_balls
        iopt[I_DOF] = DOFS[self.dof]
        iopt[I_FILM] = FILM_KINDS[self.film]
        iopt[I_DRIVE] = SCENARIOS[self.scenario]
        iopt[I_TRACTION] = TRACTIONS[self.traction]
        iopt[I_BALLBALL] = int(bool(self.ball_ball))
        iopt[I_NSLOT] = len(self.slot_azimuths_deg)
        P = np.zeros(P_SIZE)
        Ki, Ko = self.hertz_constants()
        Pd4 = 0.25 * self.diametral_clearance
        P[P_D], P[P_RB] = D, Rb
        P[P_RO], P[P_RI] = self.outer_groove_radius, self.inner_groove_radius
        P[P_ROC] = 0.5 * dm + Rb + Pd4 - self.outer_groove_radius
        P[P_RIC] = 0.5 * dm - Rb - Pd4 + self.inner_groove_radius
        P[P_MB], P[P_JB] = self.mass, self.ball_inertia
        P[P_MR], P[P_JR] = self.ring_mass, self.ring_inertia
        P[P_JROT] = self.rotor_inertia if math.isfinite(self.rotor_inertia) else 0.0
        P[P_KI], P[P_KO] = Ki, Ko
        if self.race_film == "closed_form":
            P[P_HCI], P[P_HCO] = self.race_film_coefficients()
        P[P_ALPHA] = self.race_damping
        P[P_MU], P[P_SRR], P[P_VREG] = self.traction_limit, self.traction_srr, self.traction_slip_regularisation
        P[P_G] = self.gravity
        P[P_FX] = 0.0
        P[P_FY] = -(self.radial_load - self.ring_mass * self.gravity)
        P[P_FZ] = self.axial_load
        P[P_OMEGA_FIX] = self.omega_inner
        P[P_MUROT], P[P_RC], P[P_WREG] = self.rotor_friction, self.rotor_contact_radius, self.rotor_slip_regularisation
        P[P_NROT] = self.radial_load
        P[P_SW], P[P_SL], P[P_SBLEND] = self.slot_width, self.slot_length, self.slot_blend
        # slot edges: sphere against an edge rounded with r_e along a circle of radius R_e
        hw = 0.5 * self.slot_width
        P[P_REO] = P[P_ROC] + math.sqrt(self.outer_groove_radius**2 - hw * hw)
        P[P_REI] = P[P_RIC] - math.sqrt(self.inner_groove_radius**2 - hw * hw)
        es = self.e_star_race
        re = self.slot_edge_radius
        rxo, ryo = laws_contact.relative_radii([2.0 / D, -1.0 / P[P_REO]], [2.0 / D, 1.0 / re])
        rxi, ryi = laws_contact.relative_radii([2.0 / D, 1.0 / P[P_REI]], [2.0 / D, 1.0 / re])
        P[P_KEO] = laws_contact.hertz_constant(max(rxo, ryo), min(rxo, ryo), es, self.hertz_method)
        P[P_KEI] = laws_contact.hertz_constant(max(rxi, ryi), min(rxi, ryi), es, self.hertz_method)
        P[P_QSTAB] = self.quaternion_stabilisation
        bbp = ball_ball_parameters(
            ball_radius=Rb, e_star=self.e_star_ball, yield_stress=self.yield_stress,
            damping_alpha=self.ball_ball_damping, viscosity=self.viscosity if self.film != "none" else 0.0,
            rupture_thickness=self.film_rupture_thickness, cutoff_gap=self.film_cutoff_gap,
            mu_film=self.ball_ball_mu_film, mu_boundary=self.ball_ball_mu_boundary,
            slip_regularisation=self.ball_ball_slip_regularisation, memory_time=self.plastic_memory_time,
            pressure_viscosity=self.pressure_viscosity)
        slots = np.zeros((len(self.slot_azimuths_deg), 2))
        for k, az in enumerate(self.slot_azimuths_deg):
            slots[k, 0] = math.radians(az)
            slots[k, 1] = RACES[self.slot_race]
        # a model without a film map or traction maps passes None in their places: numba then prunes the
        # map readers by type and never compiles them (the args' types select the compiled variant)
        map_ax0 = map_ax1 = map_ax2 = map_vals = map_opts = None
        if self.film == "map":
            map_ax0, map_ax1, map_ax2, map_vals, map_opts = _map_arrays(self.film_map, MAP_SPEED_AXES[
                self.film_map_speed_axis])
        counter = np.zeros(1, dtype=np.int64)
        tmap = _traction_arrays(self.traction_maps) if self.traction == "map" else None
        return (iopt, P, bbp, slots, map_ax0, map_ax1, map_ax2, map_vals, map_opts, counter, tmap)

    # state layout ---------------------------------------------------------------
    def state_layout(self) -> list[tuple[str, str]]:
        """(name, unit) of every state entry, in order."""
        out = [("Inner ring x", "m"), ("Inner ring y", "m"), ("Inner ring z", "m"), ("Inner ring angle", "rad"),
               ("Inner ring vx", "m/s"), ("Inner ring vy", "m/s"), ("Inner ring vz", "m/s"),
               ("Inner ring speed", "rad/s"), ("Rotor speed", "rad/s")]
        out += [(f"Pair {j}-{(j + 1) % self.n_balls} plastic memory", "m") for j in range(self.n_balls)]
        for j in range(self.n_balls):
            if self.dof == "6dof":
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
        k = 1.5 * max(self.hertz_constants()) ** (2.0 / 3.0) * max(self.radial_load, 100.0) ** (1.0 / 3.0)
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
        for j in range(self.n_balls):
            b = self.ball_offset(j)
            if self.dof == "6dof":
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

        Balls at ``ball_azimuths`` [rad] (default: evenly spaced from
        ``first_ball_azimuth_deg``), each in radial (and axial) equilibrium
        between the races, the inner ring in force equilibrium under F_r,
        F_a and gravity (scipy ``root`` on the same force kernel, centrifugal
        forces included for the ``"steady"`` scenario, where the balls orbit at
        the epicyclic speed and roll without slip about the axis-parallel
        direction).  ``"drop"``/``"free"``: everything at rest, the rotor at
        ``speed_rpm``; the ring gets the downward ``drop_speed``.
        ``settle=False`` returns the unloaded geometric guess.

        Raises DynamicsInputError when no equilibrium exists (a load the
        grooves cannot carry)."""
        Z = self.n_balls
        D, dm = self.ball_diameter, self.pitch_diameter
        if ball_azimuths is None:
            psi = math.radians(self.first_ball_azimuth_deg) + 2.0 * np.pi * np.arange(Z) / Z
            spacing = 2.0 * 0.5 * dm * math.sin(math.pi / Z)
            if spacing <= D:
                raise DynamicsInputError(f"n_balls = {Z}: evenly spaced balls overlap (chord {spacing:g} m <= D)")
        else:
            psi = np.asarray(ball_azimuths, dtype=float)
            if psi.shape != (Z,):
                raise DynamicsInputError(f"ball_azimuths has shape {psi.shape}; it must be ({Z},)")
        steady = self.scenario == "steady"
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
                f"radial_load = {self.radial_load:g} N, axial_load = {self.axial_load:g} N: no quasi-static "
                f"equilibrium found (force residual {err:.3g} of the mean ball load); the grooves cannot carry "
                "this load")
        if self.scenario == "drop":
            y[5] = -self.drop_speed
        diag, _, _ = forces(0.0, y, args)
        amax = float(np.max(np.abs(diag[:, [D_AI, D_AO]])))
        if amax > math.radians(self.shoulder_contact_angle_deg):
            raise DynamicsInputError(
                f"axial_load = {self.axial_load:g} N (radial_load = {self.radial_load:g} N) drives the contact angle "
                f"to {math.degrees(amax):.1f} deg, beyond the groove shoulders (shoulder_contact_angle_deg = "
                f"{self.shoulder_contact_angle_deg:g}): the bearing cannot carry it")
        return y

    def _ball_seat(self, args, y, j, psi_j, wc):
        """Radial (and axial) equilibrium of ball j for the ring in ``y``; writes y."""
        from scipy.optimize import brentq, root

        D, dm = self.ball_diameter, self.pitch_diameter
        P = args[1]
        m = self.mass
        b = self.ball_offset(j)
        six = self.dof == "6dof"
        c, s = math.cos(psi_j), math.sin(psi_j)
        dydt = np.empty_like(y)

        def set_pos(rho, z):
            if six:
                y[b:b + 3] = rho * c, rho * s, z
                y[b + 7:b + 9] = -rho * wc * s, rho * wc * c
            else:
                y[b + 1] = rho

        def res(rho, z):
            set_pos(rho, z)
            rhs(0.0, y, args, dydt)
            if six:
                return (m * (dydt[b + 7] * c + dydt[b + 8] * s + wc * wc * rho), m * dydt[b + 9])
            return (m * dydt[b + 4], 0.0)

        # groove centres in the ball's radial plane (rho, z)
        gi = np.array([P[P_RIC] + y[0] * c + y[1] * s, y[2]])
        go = np.array([P[P_ROC], 0.0])
        Ki, Ko = P[P_KI], P[P_KO]
        si, so_ = P[P_RI] - 0.5 * D, P[P_RO] - 0.5 * D
        u = go - gi
        L = float(np.hypot(*u))
        dtot = L - si - so_
        body = np.array([m * wc * wc * 0.5 * dm - m * self.gravity * s, 0.0])
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
        sol = root(lambda x: np.array(res(guess[0] + sc * x[0], guess[1] + sc * x[1])), np.zeros(2),
                   method="hybr", options=dict(xtol=1e-13))
        f = res(guess[0] + sc * sol.x[0], guess[1] + sc * sol.x[1])
        return float(np.hypot(*f))

    def _static_solve(self, args, psi, psidot, spin, ring, wc):
        """Ring force balance (hybr) around per-ball equilibria; returns (y, residual)."""
        from scipy.optimize import root

        Z = self.n_balls
        six = self.dof == "6dof"
        nr = 3 if six else 2
        y = self._pack(ring, psi, np.full(Z, 0.5 * self.pitch_diameter), np.zeros(Z), psidot, spin)
        Ki, Ko = self.hertz_constants()
        Kn = laws_contact.series_constant(Ki, Ko)
        fscale = max(self.radial_load, self.axial_load, 1.0) / Z
        scale = (max(self.radial_load, self.axial_load, 1.0) / (Z * Kn)) ** (2.0 / 3.0)
        dydt = np.empty_like(y)
        worst = [0.0]

        def residual(x):
            y[:nr] = x * scale
            worst[0] = 0.0
            for j in range(Z):
                worst[0] = max(worst[0], self._ball_seat(args, y, j, psi[j], wc))
            rhs(0.0, y, args, dydt)
            return dydt[4:4 + nr] * self.ring_mass / fscale

        x0 = np.zeros(nr)
        x0[1] = -(5.0 * self.radial_load / Z / Kn) ** (2.0 / 3.0) / scale
        if six and self.axial_load > 0.0:
            BD = self.inner_groove_radius + self.outer_groove_radius - self.ball_diameter
            x0[2] = math.sqrt(2.0 * BD * (self.axial_load / (Z * Kn)) ** (2.0 / 3.0)) * 1.2 / scale
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
        rate = self.race_damping * 2.0 * Q / self.mass
        return max(math.sqrt(2.0 * k / self.mass), rate)

    def replace(self, **changes) -> "CagelessBearing":
        """A copy with some fields changed (validated again)."""
        kw = {f.name: getattr(self, f.name) for f in fields(self)}
        unknown = set(changes) - set(kw)
        if unknown:
            key = sorted(unknown)[0]
            hint = did_you_mean(key, kw, n=2)
            raise DynamicsInputError(f"unknown bearing parameter {key!r}{hint}")
        kw.update(changes)
        return CagelessBearing(**kw)


def bearing_energy(model: CagelessBearing, y: np.ndarray) -> float:
    """Mechanical energy [J] of a state: kinetic energy of balls, ring (and
    rotor when free), Hertz potential 2/5 K delta^2.5 of every ball-race
    contact and elastic ball-ball contact, gravity and the potential -F.x of
    the constant applied ring load.  (Exact invariant of a frictionless,
    undamped, film-free, elastic run with a free ring.)"""
    args = model.args()
    P = args[1]
    Z = model.n_balls
    y = np.asarray(y, dtype=float)
    m, J = model.mass, model.ball_inertia
    E = 0.5 * model.ring_mass * float(np.sum(y[4:7] ** 2)) + 0.5 * model.ring_inertia * y[7] ** 2
    E += model.ring_mass * model.gravity * y[1] - (P[P_FX] * y[0] + P[P_FY] * y[1] + P[P_FZ] * y[2])
    pos = np.zeros((Z, 3))
    for j in range(Z):
        b = model.ball_offset(j)
        if model.dof == "6dof":
            pos[j] = y[b:b + 3]
            E += 0.5 * m * float(np.sum(y[b + 7:b + 10] ** 2)) + 0.5 * J * float(np.sum(y[b + 10:b + 13] ** 2))
        else:
            phi, r, phid, rd, om = y[b], y[b + 1], y[b + 3], y[b + 4], y[b + 5]
            pos[j] = r * math.cos(phi), r * math.sin(phi), 0.0
            E += 0.5 * m * (rd * rd + (r * phid) ** 2) + 0.5 * J * om * om
        E += m * model.gravity * pos[j, 1]
        for race in (0, 1):
            ctr = np.zeros(3) if race == 0 else y[0:3]
            Rgc, rg, K = (P[P_ROC], P[P_RO], P[P_KO]) if race == 0 else (P[P_RIC], P[P_RI], P[P_KI])
            d = pos[j] - ctr
            rho = math.hypot(d[0], d[1])
            delta = math.hypot(rho - Rgc, d[2]) - (rg - 0.5 * model.ball_diameter)
            if delta > 0.0:
                E += 0.4 * K * delta**2.5
    if model.ball_ball:
        Kbb = args[2][BB_K]
        for j in range(Z):
            k = (j + 1) % Z
            gap = float(np.linalg.norm(pos[k] - pos[j])) - model.ball_diameter
            if gap < 0.0:
                E += 0.4 * Kbb * (-gap) ** 2.5
    return E


def angular_momentum_z(model: CagelessBearing, y: np.ndarray) -> float:
    """Angular momentum [kg m^2/s] about the bearing axis of balls and inner ring."""
    Z = model.n_balls
    m, J = model.mass, model.ball_inertia
    L = model.ring_mass * (y[0] * y[5] - y[1] * y[4]) + model.ring_inertia * y[7]
    for j in range(Z):
        b = model.ball_offset(j)
        if model.dof == "6dof":
            from .rotations import quat_rotate as _qr

            w = np.empty(3)
            q = y[b + 3:b + 7] / np.linalg.norm(y[b + 3:b + 7])
            _qr(q, y[b + 10:b + 13].copy(), w)
            L += m * (y[b] * y[b + 8] - y[b + 1] * y[b + 7]) + J * w[2]
        else:
            L += m * y[b + 1] ** 2 * y[b + 3] + J * y[b + 5]
    return float(L)
