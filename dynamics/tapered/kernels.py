r"""Compiled right-hand side of the tapered roller bearing (issue 23, first step: rollers and cone).

State (:mod:`dynamics.tapered.model` names every entry)::

    [cone x, y, z, vx, vy, vz]                                  (6; the cone's spin is prescribed)
    [roller j: c (3), q (4), v (3), omega_body (3)] x Z          (13 per roller)
    [cage: c (3), q (4), v (3), omega_body (3)]                  (13; present with the option ``cage``)

c is the roller's mass centre, q the unit quaternion (scalar first, :mod:`dynamics.rotations`) that maps
the roller's body frame (x along its axis, towards the large end) to the inertial frame (x the bearing
axis, the cup fixed), omega_body the angular velocity in the body frame.  The cone translates (its axial
DOF locked, held at a displacement, or free under an axial force) and turns at the prescribed speed
Omega about x; its raceway and rib are surfaces of revolution, so its spin enters only through the
surface velocity Omega e_x x (P - d) at a contact point P (d the cone's displacement).

Contacts of roller j (laws written once in :mod:`lubrication.laws`):

* cup and cone raceways, per slice k (u_k along the axis from the roller's mid-point, radius rho_k with
  the crown): :func:`lubrication.laws.slices.slice_contact_3d` gives the interference delta, the rim
  point P and the raceway normal n (towards the roller); the approach rate is d(delta)/dt =
  -(v_roller(P) - v_race(P)).n; the slice force (:func:`lubrication.laws.slices.slice_force`, Palmgren
  k_w with eq. 11's damping alpha_e) acts on the roller along +n at P and on the cone along -n;
* flange (rib on the cone): the roller's large-end sphere (radius r_s, centre at u_s) against the rib
  line of the meridional plane (:func:`slice_contact_3d` with rho = 0 gives the centre's distance),
  delta_f = r_s - n.(S - X), Hunt-Crossley Hertz force K_f delta_f^1.5 (1 + alpha_e d(delta_f)/dt)
  (:func:`lubrication.laws.collision.hertz_force`) at P = S - r_s n.

* raceway traction (option ``traction = "paper"``): eq. 12 of paper A (linear in the sliding speed,
  :func:`lubrication.laws.traction.paper_raceway_traction`) against the tangential part of the sliding
  velocity at each loaded slice, with the Hertz half-width of the slice's line load and the
  Dowson-Toyoda film at the ideal entrainment speed (:func:`_traction_per_speed`).

* the cage (option ``cage``): a rigid body (axial position held; radial x2, three rotations) with one
  pocket per roller.  Roller j's mid-point M, seen in the cage frame, is off its pocket's mid-plane by
  s = t_j.(M - c_cage) (t_j the pocket's circumferential unit vector); the gaps to the leading and
  trailing crossbeams are Delta - s and Delta + s (Delta the pocket clearance), each a whole-roller line
  contact of :func:`lubrication.laws.cage.pocket_force` (film state, boundary state below the critical
  film, the continuous switch by default; friction against the roller surface's sliding past the beam)
  at the roller's side, M -+ rho_m t_j.  The cage rides on the cone's guide land:
  :func:`lubrication.laws.cage.guide_land_short_bearing` (film force in the radial plane),
  :func:`lubrication.laws.cage.guide_land_torque` (Couette drag), and below the critical film a
  contact k_h (h_crit - h) with boundary friction; the land's reaction acts on the cone.

Not yet in this step (the fidelity levels part 2 adds): flange friction, the side-beam squeeze (axial
cage contacts), gravity.  Equations of motion: Newton for the mass
centres, Euler's equations with I_x != I_y = I_z (:func:`dynamics.rotations.euler_rate`, gyroscopic
terms included) and the quaternion kinematics (:func:`dynamics.rotations.quat_derivative`).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from lubrication.laws.cage import guide_land_short_bearing, guide_land_torque, pocket_force
from lubrication.laws.collision import hertz_force
from lubrication.laws.film import dowson_toyoda_central
from lubrication.laws.jit import INLINE, JIT
from lubrication.laws.slices import slice_contact_3d, slice_force
from lubrication.laws.traction import paper_raceway_traction

from ..rotations import euler_rate, quat_derivative, quat_rotate, quat_rotate_inverse

# float parameters
(P_Z, P_NS, P_M, P_IX, P_IY, P_MC, P_OMEGA, P_FA, P_FR, P_AXIAL, P_KW, P_KF, P_ALPHA, P_RS, P_US, P_UC,
 P_CUPX, P_CUPR, P_CUPNX, P_CUPNR, P_CONX, P_CONR, P_CONNX, P_CONNR, P_FLX, P_FLR, P_FLNX, P_FLNR,
 P_CONTACTS, P_QSTAB, P_TRACTION, P_ETA, P_PVC, P_EP, P_RXO, P_RXI, P_UE, P_WIDTH,
 P_CAGE, P_MCG, P_ICX, P_ICT, P_POCKET, P_LEN, P_RHOM, P_HCRIT, P_KH, P_CH, P_MUBD, P_SWITCH, P_RLAND, P_CLAND,
 P_BLAND, P_HLAND) = range(54)
P_SIZE = 54
TRACTION_NONE, TRACTION_PAPER = 0.0, 1.0
_dowson_toyoda = njit(**INLINE)(dowson_toyoda_central)   # the law of lubrication.laws.film, compiled here
AXIAL_LOCKED, AXIAL_FORCE = 0.0, 1.0
N_CONE, NB = 6, 13


@njit(**JIT)
def _cross(a0, a1, a2, b0, b1, b2):
    return a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0


@njit(**INLINE)
def _load_roller(F, T, j, r0, r1, r2, f0, f1, f2):
    """Add the force (f0, f1, f2) acting at r (from roller j's mass centre) to its force and torque."""
    F[j, 0] += f0
    F[j, 1] += f1
    F[j, 2] += f2
    t0, t1, t2 = _cross(r0, r1, r2, f0, f1, f2)
    T[j, 0] += t0
    T[j, 1] += t1
    T[j, 2] += t2


@njit(**INLINE)
def _traction_per_speed(load, radius, P):
    """Eq. 12's traction per sliding speed [N s/m] of a slice carrying ``load`` [N] on a raceway of
    reduced radius ``radius``: pi eps eta sqrt(R'/(2 h0)) times the slice width, with the Hertz half-width
    b = sqrt(8 w R'/(pi E')) of the slice's line load w and the Dowson-Toyoda central film h0 at the ideal
    entrainment speed (:func:`lubrication.laws.traction.paper_raceway_traction`)."""
    w = load / P[P_WIDTH]
    ep = P[P_EP]
    b = math.sqrt(8.0 * w * radius / (math.pi * ep))
    h0 = radius * _dowson_toyoda(P[P_ETA] * P[P_UE] / (ep * radius), P[P_PVC] * ep, w / (ep * radius))
    return paper_raceway_traction(1.0, P[P_ETA], radius, h0, b) * P[P_WIDTH]


@njit(**JIT)
def contact_forces(y, P, U, RHO, F, T, Fc, loads, Fg, Tg):
    """Contact forces and torques: F[j] force on roller j [N], T[j] torque about its mass centre
    (inertial frame) [N m], Fc the force of all rollers (and the cage) on the cone [N], loads[j] =
    (cup, cone, flange, pocket) sums of the contact forces' magnitudes [N]; Fg, Tg the force [N] and the
    torque about its centre [N m] on the cage."""
    Z = int(P[P_Z])
    ns = int(P[P_NS])
    F[:, :] = 0.0
    T[:, :] = 0.0
    Fc[:] = 0.0
    Fg[:] = 0.0
    Tg[:] = 0.0
    loads[:, :] = 0.0
    if P[P_CONTACTS] == 0.0:
        return
    dx, dy, dz = y[0], y[1], y[2]
    vcx, vcy, vcz = y[3], y[4], y[5]
    om = P[P_OMEGA]
    ex_b = np.array([1.0, 0.0, 0.0])
    e = np.empty(3)
    wi = np.empty(3)
    for j in range(Z):
        b = N_CONE + j * NB
        c0, c1, c2 = y[b], y[b + 1], y[b + 2]
        q = y[b + 3:b + 7] / math.sqrt(y[b + 3] ** 2 + y[b + 4] ** 2 + y[b + 5] ** 2 + y[b + 6] ** 2)
        v0, v1, v2 = y[b + 7], y[b + 8], y[b + 9]
        quat_rotate(q, ex_b, e)
        quat_rotate(q, y[b + 10:b + 13], wi)          # angular velocity, inertial frame
        e0, e1, e2 = e[0], e[1], e[2]
        # the roller's mid-point (slice coordinates u are measured from it)
        m0, m1, m2 = c0 - P[P_UC] * e0, c1 - P[P_UC] * e1, c2 - P[P_UC] * e2
        for race in range(2):
            if race == 0:
                px, pr, nx, nr = P[P_CUPX], P[P_CUPR], P[P_CUPNX], P[P_CUPNR]
                ox, oy, oz = 0.0, 0.0, 0.0
            else:
                px, pr, nx, nr = P[P_CONX], P[P_CONR], P[P_CONNX], P[P_CONNR]
                ox, oy, oz = dx, dy, dz
            for k in range(ns):
                u = U[k]
                s0, s1, s2 = m0 + u * e0 - ox, m1 + u * e1 - oy, m2 + u * e2 - oz
                delta, q0, q1, q2, n0, n1, n2 = slice_contact_3d(s0, s1, s2, e0, e1, e2, RHO[k], px, pr, nx, nr)
                if delta <= 0.0:
                    continue
                P0, P1, P2 = q0 + ox, q1 + oy, q2 + oz     # contact point, inertial
                r0, r1, r2 = P0 - c0, P1 - c1, P2 - c2
                w0, w1, w2 = _cross(wi[0], wi[1], wi[2], r0, r1, r2)
                u0, u1, u2 = v0 + w0, v1 + w1, v2 + w2     # roller surface velocity at P
                if race == 1:                               # cone surface: v_d + Omega e_x x (P - d)
                    a0, a1, a2 = _cross(om, 0.0, 0.0, q0, q1, q2)
                    u0 -= vcx + a0
                    u1 -= vcy + a1
                    u2 -= vcz + a2
                ddot = -(u0 * n0 + u1 * n1 + u2 * n2)
                f = slice_force(delta, ddot, P[P_KW], P[P_ALPHA])
                if f <= 0.0:
                    continue
                f0, f1, f2 = f * n0, f * n1, f * n2
                if P[P_TRACTION] == TRACTION_PAPER:
                    # eq. 12 against the sliding velocity's tangential part, per unit length times the width
                    un = u0 * n0 + u1 * n1 + u2 * n2
                    s0, s1, s2 = u0 - un * n0, u1 - un * n1, u2 - un * n2
                    c = _traction_per_speed(f, P[P_RXO] if race == 0 else P[P_RXI], P)
                    f0 -= c * s0
                    f1 -= c * s1
                    f2 -= c * s2
                _load_roller(F, T, j, r0, r1, r2, f0, f1, f2)
                loads[j, race] += f
                if race == 1:
                    Fc[0] -= f0
                    Fc[1] -= f1
                    Fc[2] -= f2
        # flange: the large-end sphere against the rib (on the cone)
        us = P[P_US]
        s0, s1, s2 = m0 + us * e0 - dx, m1 + us * e1 - dy, m2 + us * e2 - dz
        d0, _, _, _, n0, n1, n2 = slice_contact_3d(s0, s1, s2, e0, e1, e2, 0.0, P[P_FLX], P[P_FLR],
                                                   P[P_FLNX], P[P_FLNR])
        delta = P[P_RS] + d0
        if delta > 0.0:
            q0, q1, q2 = s0 - P[P_RS] * n0, s1 - P[P_RS] * n1, s2 - P[P_RS] * n2
            P0, P1, P2 = q0 + dx, q1 + dy, q2 + dz
            r0, r1, r2 = P0 - c0, P1 - c1, P2 - c2
            w0, w1, w2 = _cross(wi[0], wi[1], wi[2], r0, r1, r2)
            a0, a1, a2 = _cross(om, 0.0, 0.0, q0, q1, q2)
            u0, u1, u2 = v0 + w0 - vcx - a0, v1 + w1 - vcy - a1, v2 + w2 - vcz - a2
            ddot = -(u0 * n0 + u1 * n1 + u2 * n2)
            f = hertz_force(delta, ddot, P[P_KF], P[P_ALPHA])
            if f > 0.0:
                f0, f1, f2 = f * n0, f * n1, f * n2
                _load_roller(F, T, j, r0, r1, r2, f0, f1, f2)
                loads[j, 2] += f
                Fc[0] -= f0
                Fc[1] -= f1
                Fc[2] -= f2
        if P[P_CAGE] != 0.0:
            _pocket(j, y, P, c0, c1, c2, v0, v1, v2, wi, e0, e1, e2, m0, m1, m2, F, T, loads, Fg, Tg)
    if P[P_CAGE] != 0.0:
        _guide_land(y, P, Fc, Fg, Tg)


@njit(**INLINE)
def _pocket(j, y, P, c0, c1, c2, v0, v1, v2, wi, e0, e1, e2, m0, m1, m2, F, T, loads, Fg, Tg):
    """Roller j against the crossbeams of its pocket (module docstring): forces on the roller and the cage."""
    Z = int(P[P_Z])
    b = N_CONE + Z * NB
    g0, g1, g2 = y[b], y[b + 1], y[b + 2]
    qc = y[b + 3:b + 7] / math.sqrt(y[b + 3] ** 2 + y[b + 4] ** 2 + y[b + 5] ** 2 + y[b + 6] ** 2)
    phi = 2.0 * math.pi * j / Z
    tb = np.array([0.0, -math.sin(phi), math.cos(phi)])
    t = np.empty(3)
    quat_rotate(qc, tb, t)                        # the pocket's circumferential unit vector, inertial
    wc = np.empty(3)
    quat_rotate(qc, y[b + 10:b + 13], wc)         # cage angular velocity, inertial
    s = t[0] * (m0 - g0) + t[1] * (m1 - g1) + t[2] * (m2 - g2)
    for side in range(2):
        sg = 1.0 if side == 0 else -1.0           # leading beam (+t), trailing beam (-t)
        gap = P[P_POCKET] - sg * s
        # contact point on the roller's side facing the beam
        p0, p1, p2 = m0 + sg * P[P_RHOM] * t[0], m1 + sg * P[P_RHOM] * t[1], m2 + sg * P[P_RHOM] * t[2]
        r0, r1, r2 = p0 - c0, p1 - c1, p2 - c2
        a0, a1, a2 = _cross(wi[0], wi[1], wi[2], r0, r1, r2)
        h0, h1, h2 = p0 - g0, p1 - g1, p2 - g2
        k0, k1, k2 = _cross(wc[0], wc[1], wc[2], h0, h1, h2)
        u0 = v0 + a0 - y[b + 7] - k0
        u1 = v1 + a1 - y[b + 8] - k1
        u2 = v2 + a2 - y[b + 9] - k2
        un = u0 * t[0] + u1 * t[1] + u2 * t[2]
        s0, s1, s2 = u0 - un * t[0], u1 - un * t[1], u2 - un * t[2]
        vs = math.sqrt(s0 * s0 + s1 * s1 + s2 * s2)
        q, f = pocket_force(gap, -sg * un, vs, P[P_RHOM], P[P_LEN], P[P_ETA], P[P_HCRIT], P[P_KH], P[P_CH],
                            P[P_MUBD], int(P[P_SWITCH]))
        if q <= 0.0 and f == 0.0:
            continue
        f0, f1, f2 = -sg * q * t[0], -sg * q * t[1], -sg * q * t[2]
        if vs > 0.0:
            f0 -= f * s0 / vs
            f1 -= f * s1 / vs
            f2 -= f * s2 / vs
        _load_roller(F, T, j, r0, r1, r2, f0, f1, f2)
        loads[j, 3] += q
        Fg[0] -= f0
        Fg[1] -= f1
        Fg[2] -= f2
        x0, x1, x2 = _cross(h0, h1, h2, -f0, -f1, -f2)
        Tg[0] += x0
        Tg[1] += x1
        Tg[2] += x2


@njit(**INLINE)
def _guide_land(y, P, Fc, Fg, Tg):
    """The cage's centering surface on the cone's guide land (module docstring)."""
    Z = int(P[P_Z])
    b = N_CONE + Z * NB
    qc = y[b + 3:b + 7] / math.sqrt(y[b + 3] ** 2 + y[b + 4] ** 2 + y[b + 5] ** 2 + y[b + 6] ** 2)
    wc = np.empty(3)
    quat_rotate(qc, y[b + 10:b + 13], wc)
    # the land (journal) relative to the cage (bearing), in the radial plane (y, z)
    ex, ey = y[1] - y[b + 1], y[2] - y[b + 2]
    vx, vy = y[4] - y[b + 8], y[5] - y[b + 9]
    r, c, w = P[P_RLAND], P[P_CLAND], P[P_BLAND]
    ecc = math.sqrt(ex * ex + ey * ey)
    if ecc >= c:
        ecc = c * (1.0 - 1e-9)
    fx, fy = guide_land_short_bearing(ex, ey, vx, vy, r, c, w, P[P_ETA], r * (P[P_OMEGA] + wc[0]))
    gap = c - math.sqrt(ex * ex + ey * ey)
    torque = guide_land_torque(ecc / c, r, c, w, P[P_ETA], P[P_OMEGA], wc[0])
    if gap < P[P_HLAND] and ecc > 0.0:
        nx, ny = ex / ecc, ey / ecc                 # from the cage's centre towards the land's
        vr = vx * nx + vy * ny                       # rate at which the land closes on the bore
        qs = P[P_KH] * (P[P_HLAND] - gap) + P[P_CH] * vr
        if qs > 0.0:                                 # on the land, back towards the cage's centre
            fx -= qs * nx
            fy -= qs * ny
            slide = r * (P[P_OMEGA] - wc[0])
            torque += P[P_MUBD] * qs * r * (1.0 if slide > 0.0 else (-1.0 if slide < 0.0 else 0.0))
    # (fx, fy) acts on the land (journal): the cage gets the opposite, the cone the reaction
    Fg[1] -= fx
    Fg[2] -= fy
    Fc[1] += fx
    Fc[2] += fy
    Tg[0] += torque


@njit(**JIT)
def rhs(t, y, args, dydt):
    """dy/dt of the tapered roller bearing (module docstring); ``args = (P, U, RHO)``."""
    P, U, RHO = args
    Z = int(P[P_Z])
    F = np.empty((Z, 3))
    T = np.empty((Z, 3))
    Fc = np.empty(3)
    loads = np.empty((Z, 4))
    Fg = np.empty(3)
    Tg = np.empty(3)
    contact_forces(y, P, U, RHO, F, T, Fc, loads, Fg, Tg)
    # cone: translation under the rollers' forces, F_r along +y, F_a along -x (closing the bearing)
    mc = P[P_MC]
    dydt[0] = y[3]
    dydt[1] = y[4]
    dydt[2] = y[5]
    if P[P_AXIAL] == AXIAL_FORCE:
        dydt[3] = (Fc[0] - P[P_FA]) / mc
    else:
        dydt[0] = 0.0
        dydt[3] = 0.0
    dydt[4] = (Fc[1] + P[P_FR]) / mc
    dydt[5] = Fc[2] / mc
    inertia = np.array([P[P_IX], P[P_IY], P[P_IY]])
    tb = np.empty(3)
    m = P[P_M]
    for j in range(Z):
        b = N_CONE + j * NB
        q = y[b + 3:b + 7]
        dydt[b] = y[b + 7]
        dydt[b + 1] = y[b + 8]
        dydt[b + 2] = y[b + 9]
        quat_derivative(q, y[b + 10:b + 13], dydt[b + 3:b + 7], P[P_QSTAB])
        dydt[b + 7] = F[j, 0] / m
        dydt[b + 8] = F[j, 1] / m
        dydt[b + 9] = F[j, 2] / m
        qn = q / math.sqrt(q[0] ** 2 + q[1] ** 2 + q[2] ** 2 + q[3] ** 2)
        quat_rotate_inverse(qn, T[j], tb)
        euler_rate(inertia, y[b + 10:b + 13], tb, dydt[b + 10:b + 13])
    if P[P_CAGE] != 0.0:
        b = N_CONE + Z * NB
        q = y[b + 3:b + 7]
        dydt[b] = 0.0                                  # axial position held (no side-beam contact yet)
        dydt[b + 1] = y[b + 8]
        dydt[b + 2] = y[b + 9]
        quat_derivative(q, y[b + 10:b + 13], dydt[b + 3:b + 7], P[P_QSTAB])
        dydt[b + 7] = 0.0
        dydt[b + 8] = Fg[1] / P[P_MCG]
        dydt[b + 9] = Fg[2] / P[P_MCG]
        qn = q / math.sqrt(q[0] ** 2 + q[1] ** 2 + q[2] ** 2 + q[3] ** 2)
        quat_rotate_inverse(qn, Tg, tb)
        euler_rate(np.array([P[P_ICX], P[P_ICT], P[P_ICT]]), y[b + 10:b + 13], tb, dydt[b + 10:b + 13])


@njit(**JIT)
def loads_many(Y, args):
    """(n, Z, 4) cup, cone, flange and pocket loads [N] of each roller at each sampled state."""
    P, U, RHO = args
    Z = int(P[P_Z])
    out = np.empty((Y.shape[0], Z, 4))
    F = np.empty((Z, 3))
    T = np.empty((Z, 3))
    Fc = np.empty(3)
    Fg = np.empty(3)
    Tg = np.empty(3)
    for i in range(Y.shape[0]):
        contact_forces(Y[i], P, U, RHO, F, T, Fc, out[i], Fg, Tg)
    return out
