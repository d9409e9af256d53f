"""The compiled right-hand side of the cage-less bearing: ball-race and ball-ball contacts, slots, rings.

Part of :mod:`lubedyn.dynamics.cageless` (the package docstring gives the overview)."""
from __future__ import annotations

import math

from numba import njit, types
from numba.extending import overload
import numpy as np

from lubedyn.lubrication.laws.collision import hertz_force
from lubedyn.lubrication.laws.jit import INLINE, JIT
from lubedyn.lubrication.laws.traction import traction_coefficient

from .. import contacts as C
from ..contacts import FILM_NONE, ball_ball_friction_coefficient, ball_ball_normal, plastic_memory_rate
from ..interp import HERMITE, hermite3, interp3
from ..specialise import register_kernel, specialise
from .layout import (D_AI, D_AO, D_BBN, D_BBT, D_BBX, D_BBY, D_BBZ, D_GAP, D_H, D_PHASE, D_PSI, D_PSIDOT, D_QE, D_QI,
    D_QO, D_SPIN, D_SRRI, D_SRRO, D_VSI, D_VSO, NB_6DOF, NB_PLANAR, N_DIAG, N_RING, N_RING_DIAG)

# ----------------------------------------------------------------------------- kernels
@njit(**JIT)
def _traction_from_map(tmap, race, Q, ue, vs, counter):
    """Traction coefficient of the EHL map of ``race`` (load, entrainment speed, slide-to-roll ratio).

    Below the map's first slide-to-roll node the coefficient is linear in the SRR
    (lubedyn.film_points, "Traction axis").  ``tmap`` is None in a model without
    traction maps: numba prunes the ``is None`` branch by type, so such a model never
    compiles the map readers (about a third of the cold compile of ``rhs``)."""
    if tmap is None:
        return math.nan
    ax0, ax1, ax2, vals, opts = tmap.ax0, tmap.ax1, tmap.ax2, tmap.values, tmap.opts
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


def _film_map_arrays(film_map):
    """The ball-ball film map's arrays (:class:`lubedyn.dynamics.cageless.layout.MapArrays`) as
    :func:`lubedyn.dynamics.contacts.ball_ball_normal` takes them, or five None without a map.  Compiled
    by type (:func:`_film_map_arrays_typed`): a model without a map passes None-typed arrays, and numba
    never compiles the map readers for it."""
    if film_map is None:
        return None, None, None, None, None
    return film_map.ax0, film_map.ax1, film_map.ax2, film_map.values, film_map.opts


@overload(_film_map_arrays, inline="always")
def _film_map_arrays_typed(film_map):
    # one implementation per type (an ``is None`` test in one compiled function would unify the two
    # returns into optional arrays, and the readers' choice by the values' dimension would not prune)
    if isinstance(film_map, types.NoneType):
        return lambda film_map: (None, None, None, None, None)
    return lambda film_map: (film_map.ax0, film_map.ax1, film_map.ax2, film_map.values, film_map.opts)


@njit(**INLINE)
def _tangential(x0, x1, x2, n0, n1, n2):
    """The part of (x0, x1, x2) in the plane normal to the unit vector n: x - (x . n) n."""
    xn = x0 * n0 + x1 * n1 + x2 * n2
    return x0 - xn * n0, x1 - xn * n1, x2 - xn * n2


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
    s0, s1, s2 = _tangential(vb0 - vr0, vb1 - vr1, vb2 - vr2, n0, n1, n2)
    e0, e1, e2 = _tangential(0.5 * (vb0 + vr0) - vp0, 0.5 * (vb1 + vr1) - vp1, 0.5 * (vb2 + vr2) - vp2, n0, n1, n2)
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
    far = 0.5 * P.sl + 10.0 * P.sblend
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
        ws = _smooth_in(s_arc, 0.5 * P.sl, P.sblend)
        if ws > best_s:
            best_s = ws
        wz = _smooth_in(pz, 0.5 * P.sw, P.sblend)
        if ws * wz > best:
            best = ws * wz
    return best, best_s


@njit(**INLINE)
def _slot_directions(P, slots, ring_theta, sdir, cfar):
    """sdir[k] <- (cos, sin) of slot k's azimuth (plus the ring angle for an
    inner-ring slot); cfar[race] <- cos of 1.01 times the angular reach
    far/R_race of a slot's weight on that race (-2 when it reaches past pi),
    for the dot-product skip of :func:`_slot_weight`."""
    far = 0.5 * P.sl + 10.0 * P.sblend
    for race in range(2):
        R_race = P.ro + P.roc if race == 0 else P.ric - P.ri
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
    D = P.d
    Rb = P.rb
    halfw = 0.5 * P.sw
    c0, c1, c2 = cpos[j, 0], cpos[j, 1], cpos[j, 2]
    v0, v1, v2 = cvel[j, 0], cvel[j, 1], cvel[j, 2]
    w0, w1, w2 = cw[j, 0], cw[j, 1], cw[j, 2]
    alpha, mu_lim, srr_ref, v_reg = P.alpha, P.mu, P.srr, P.vreg
    F0 = F1 = F2 = T0 = T1 = T2 = 0.0
    R0 = R1 = R2 = R3 = 0.0
    if want:
        diag[j, D_QE] = 0.0
    for race in range(2):
        if race == 0:
            Rgc, rg, K, KE, RE = P.roc, P.ro, P.ko, P.keo, P.reo
            ctr0, ctr1, ctr2 = 0.0, 0.0, 0.0
            vc0, vc1, vc2 = 0.0, 0.0, 0.0
            wr = 0.0
            th = 0.0
        else:
            Rgc, rg, K, KE, RE = P.ric, P.ri, P.ki, P.kei, P.rei
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
            race == 1, Rb, alpha, mu_lim, srr_ref, v_reg, P.hco if race == 0 else P.hci, tmap,
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
    :func:`lubedyn.dynamics.rotations.quat_rotate`; pass (w, -x, -y, -z) for R^T v)."""
    tx = 2.0 * (y * v2 - z * v1)
    ty = 2.0 * (z * v0 - x * v2)
    tz = 2.0 * (x * v1 - y * v0)
    return v0 + w * tx + (y * tz - z * ty), v1 + w * ty + (z * tx - x * tz), v2 + w * tz + (x * ty - y * tx)


@njit(**JIT)
def _evaluate(t, y, args, dydt, diag, ring_diag):
    P, bbp, slots, counter, tmap = args.P[0], args.bbp[0], args.slots, args.counter, args.traction_maps
    map_ax0, map_ax1, map_ax2, map_vals, map_opts = _film_map_arrays(args.film_map)
    want = diag.shape[0] > 0
    Z = P.z
    dof = P.dof
    nb = NB_6DOF if dof == 1 else NB_PLANAR
    off = N_RING + Z
    mb = P.mb
    Jb = P.jb
    g = P.g
    Rb = P.rb
    D = P.d
    use_map = P.traction == 1
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
    if P.ballball == 1:
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
            if gap > 0.0 and (P.film == FILM_NONE or gap >= bbp.hcut):
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
            Fn, h, de, phase, share = ball_ball_normal(gap, vapp, ue, dmax, bbp, P.film, map_ax0, map_ax1,
                                                       map_ax2, map_vals, map_opts, counter)
            dydt[N_RING + j] = plastic_memory_rate(de, share * vapp, dmax, Fn, bbp)
            f0, f1, f2 = Fn * n0, Fn * n1, Fn * n2
            ft = 0.0
            if Fn > 0.0:
                # sliding velocity of k's surface relative to j's at the contact point
                s0, s1, s2 = _tangential(r0 + (wk1 * -a2 - wk2 * -a1) - (wj1 * a2 - wj2 * a1),
                                         r1 + (wk2 * -a0 - wk0 * -a2) - (wj2 * a0 - wj0 * a2),
                                         r2 + (wk0 * -a1 - wk1 * -a0) - (wj0 * a1 - wj1 * a0), n0, n1, n2)
                vs = math.sqrt(s0 * s0 + s1 * s1 + s2 * s2)
                if vs > 0.0:
                    mu = ball_ball_friction_coefficient(h, Fn, vs, bbp)
                    ft = mu * Fn * math.tanh(vs / bbp.vreg)
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
    stab = P.qstab
    for j in range(Z):
        b = off + j * nb
        Fb[j, 1] -= mb * g
        if dof == 1:
            for k in range(3):
                dydt[b + k] = y[b + 7 + k]
                dydt[b + 7 + k] = Fb[j, k] / mb
            # dq/dt = q * (0, w_b) / 2 - k (|q|^2 - 1) q (lubedyn.dynamics.rotations.quat_derivative)
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
            # Euler's equations for a sphere (J1 = J2 = J3 = Jb; lubedyn.dynamics.rotations.euler_rate)
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
    mr = P.mr
    dydt[0] = y[4]
    dydt[1] = y[5]
    dydt[2] = y[6]
    dydt[3] = y[7]
    dydt[4] = (RF[0] + P.fx) / mr
    dydt[5] = (RF[1] + P.fy) / mr - g
    if dof == 1:
        dydt[6] = (RF[2] + P.fz) / mr
    else:
        dydt[2] = 0.0
        dydt[6] = 0.0
    drive = P.drive
    Tf = 0.0
    if drive == 0:
        dydt[7] = 0.0
        dydt[8] = 0.0
    elif drive == 1:
        Tf = P.murot * P.nrot * P.rc * math.tanh((y[8] - y[7]) / P.wreg)
        dydt[7] = (RF[3] + Tf) / P.jr
        dydt[8] = -Tf / P.jrot if P.jrot > 0.0 else 0.0
    else:
        dydt[7] = RF[3] / P.jr
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


def _forces_impl(evaluate, t, y, args):
    Z = args.P[0].z
    dydt = np.empty(y.size)
    diag = np.zeros((Z, N_DIAG))
    ring_diag = np.zeros(N_RING_DIAG)
    evaluate(t, y, args, dydt, diag, ring_diag)
    return diag, ring_diag, dydt


def _forces_many_impl(evaluate, t, Y, args):
    m = Y.shape[0]
    Z = args.P[0].z
    D = np.zeros((m, Z, N_DIAG))
    R = np.zeros((m, N_RING_DIAG))
    dydt = np.empty(Y.shape[1])
    for i in range(m):
        evaluate(t[i], Y[i], args, dydt, D[i], R[i])
    return D, R


# the right-hand side's body reached through a function pointer (lubedyn.dynamics.specialise): compiled once,
# not linked and re-optimised a second time into these kernels (forces_many: 4.5-5.8 s of a cold run
# when it was, forces 1 s)
def _evaluate_signature(types_):
    """``_evaluate(t, y, args, dydt, diag, ring_diag)`` as the kernels call it (C-contiguous arrays)."""
    v = types.float64[::1]
    return types.void(types.float64, v, types_["args"], v, types.float64[:, ::1], v)


register_kernel(_forces_impl, evaluate=_evaluate_signature)
register_kernel(_forces_many_impl, evaluate=_evaluate_signature)


def forces(t, y, args):
    """Contact forces at a state: ``(diag (Z, N_DIAG), ring_diag (N_RING_DIAG,), dydt)``.

    Columns of ``diag`` are named by :data:`DIAG_NAMES`; the ball-ball columns
    of row j belong to the pair (j, j+1 mod Z) and give the force on ball j+1.  The model's body is
    reached through a function pointer (:mod:`lubedyn.dynamics.specialise`), compiled once with ``rhs``."""
    return specialise(_forces_impl, evaluate=_evaluate)(float(t), np.ascontiguousarray(y, dtype=np.float64), args)


def forces_example(args):
    """``(kernel, example arguments)`` of :func:`forces` (:func:`lubedyn.dynamics.specialise.compile_in_background`)."""
    return specialise(_forces_impl, evaluate=_evaluate), (0.0, np.zeros(1), args)


def forces_many_example(args):
    """``(kernel, example arguments)`` of :func:`forces_many` (:func:`lubedyn.dynamics.specialise.compile_in_background`)."""
    return specialise(_forces_many_impl, evaluate=_evaluate), (np.zeros(1), np.zeros((1, 1)), args)


def forces_many(t, Y, args):
    """:func:`forces` at every row of ``Y`` (shape (m, n)) at times ``t``: ``(diag (m, Z, N_DIAG), ring (m,
    N_RING_DIAG))``, the same numbers as :func:`forces` row by row."""
    t = np.ascontiguousarray(t, dtype=np.float64)
    Y = np.ascontiguousarray(Y, dtype=np.float64)
    return specialise(_forces_many_impl, evaluate=_evaluate)(t, Y, args)
