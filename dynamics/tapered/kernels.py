r"""Compiled right-hand side of the tapered roller bearing: cone, 17 rollers and the cage.

State (:mod:`lubedyn.dynamics.tapered.layout`; :class:`lubedyn.dynamics.tapered.model.TaperedBearing` names every entry)::

    [cone x, y, z, vx, vy, vz]                                  (6; the cone's spin is prescribed)
    [roller j: c (3), q (4), v (3), omega_body (3)] x Z          (13 per roller)
    [cage: c (3), q (4), v (3), omega_body (3)]                  (13; present unless pocket = "none")
    [cone tilt: theta_y, theta_z, theta_y', theta_z']             (4; present with cone_tilt = "free")

c is the roller's mass centre, q the unit quaternion (scalar first, :mod:`lubedyn.dynamics.rotations`) that maps
the roller's body frame (x along its axis, towards the large end) to the inertial frame (x the bearing
axis, the cup fixed), omega_body the angular velocity in the body frame.  The cone translates (its axial
DOF held at a displacement, or free under an axial force) and turns at the prescribed speed
Omega about x; its raceway and rib are surfaces of revolution, so its spin enters only through the
surface velocity Omega e_x x (P - d) at a contact point P (d the cone's displacement).

Equations of motion, inertial frame (so the centrifugal and gyroscopic loads are not added by hand:
they are what the contacts must supply to keep the bodies on their orbits)::

    m c'' = sum F - m g e_y                                       (Newton, gravity optional)
    I omega_body' + omega_body x (I omega_body) = R(q)^T sum T     (Euler, I = diag(I_x, I_y, I_y))
    q' = q * (0, omega_body)/2  (+ a drift term pulling |q| to 1)

paper A's eqs. 47-51 in their body frame; eq. 50's third row is read with omega_x omega_y (the print's garbled product; docs/paper_a.md),
which is what Euler's equations give.

Contacts of roller j (laws written once in :mod:`lubedyn.lubrication.laws`):

* cup and cone raceways, per slice k (u_k along the axis from the roller's mid-point, radius rho_k with
  the crown): :func:`lubedyn.lubrication.laws.slices.slice_contact_3d` gives the interference delta, the rim
  point P and the raceway normal n (towards the roller); the approach rate is d(delta)/dt =
  -(v_roller(P) - v_race(P)).n; the slice force (:func:`lubedyn.lubrication.laws.slices.slice_force`, Palmgren
  k_w with eq. 11's damping alpha_e) acts on the roller along +n at P and on the cone along -n;
* flange (rib on the cone): the roller's large-end sphere (radius r_s, centre at u_s) against the rib
  line of the meridional plane (:func:`slice_contact_3d` with rho = 0 gives the centre's distance),
  delta_f = r_s - n.(S - X), Hunt-Crossley Hertz force K_f delta_f^1.5 (1 + alpha_e d(delta_f)/dt)
  (:func:`lubedyn.lubrication.laws.collision.hertz_force`) at P = S - r_s n.

* raceway traction (option ``traction``): against the tangential part of the sliding velocity at each
  loaded slice (rolling direction and the axial sliding a skewed roller makes, one vector), with the
  Hertz half-width b = sqrt(8 w R'/(pi E')) of the slice's line load w and the Dowson-Toyoda film at the
  ideal entrainment speed with the race's film viscosity (``P.etao`` cup, ``P.etai`` cone: the films'
  Newtonian viscosity, or the one that makes the grease's EHL film, :func:`strip_film`): "paper" eq. 12 (linear in the sliding speed,
  :func:`lubedyn.lubrication.laws.traction.paper_raceway_traction`), "limited" the Herschel-Bulkley strip law
  with Barus consistency and a limiting shear stress (an extension,
  :func:`lubedyn.lubrication.laws.traction.limited_strip_traction`) in series with the film's elastic shear
  (Johnson-Tevaarwerk's slope 2 G b^2/(u_e h), :func:`lubedyn.lubrication.laws.traction.elastic_limited`), "map"
  the roller EHL maps' film traction coefficient at the slice's line load and slide-to-roll ratio v_s/u_e
  times the slice load (:func:`map_traction_coefficient`), "none";
* flange friction (option ``flange_friction``, eqs. 22-23, :func:`lubedyn.lubrication.laws.flange.flange_friction`):
  mu_a q exp(-B lambda^C) + w f_grease against the roller end's sliding on the rib, f_grease eq. 27's
  limited Herschel-Bulkley traction over the Hertz ellipse (semi-axes and p0 scale as q^(1/3) from the
  exact point law at 1 N), w = 1 ("paper") or the fluid share ("load_share"); the rib film h and
  lambda = h/sigma are evaluated once at the start's flange load and the ideal rib entrainment speed
  (a fixed film: the film's change with load in the run is the next fidelity level);

* the cage (option ``cage``): a rigid body (six DOF with the side beams, below; without them its axial position held) with one
  pocket per roller.  Roller j's mid-point M, seen in the cage frame, is off its pocket's mid-plane by
  s = t_j.(M - c_cage) (t_j the pocket's circumferential unit vector); the gaps to the leading and
  trailing crossbeams are Delta - s and Delta + s (Delta the pocket clearance), each a whole-roller line
  contact of :func:`lubedyn.lubrication.laws.cage.pocket_force` (film state, boundary state below the critical
  film, the continuous switch by default; friction against the roller surface's sliding past the beam)
  at the roller's side, M -+ rho_m t_j.  The cage rides on the cone's guide land:
  :func:`lubedyn.lubrication.laws.cage.guide_land_short_bearing` (film force in the radial plane),
  :func:`lubedyn.lubrication.laws.cage.guide_land_torque` (Couette drag), and below the critical film a
  contact k_h (h_crit - h) with boundary friction pushing the land back towards the cage's centre; the
  land's reaction acts on the cone.  These are the "film" levels of the options ``pocket`` and
  ``guide_land``.  The "contact" levels (the "contact only" fidelity, the cheapest that holds the
  cage; a pocket or land film law replaces them through the same option code): a roller touches a
  crossbeam when its mid-point is off the pocket's mid-plane by more than the pocket clearance Delta
  (0.27 mm), a line contact of the whole roller (Palmgren's law with E' of steel on the cage's polyamide,
  :func:`lubedyn.lubrication.laws.slices.line_constant`, eq. 11's damping) with friction mu_bd tanh(v_s/v_reg)
  against the sliding; the land touches the cage's bore when their centres are more than the radial
  clearance (0.25 mm) apart, a line contact of the land's width, with friction torque mu_bd q r.

* side beams (option ``side_beams``, eqs. 39-40): each roller end against its pocket's side beam across the
  axial clearance Delta' (squeeze film and boundary state, or contact only); with them the cage has all six
  DOF, without them its axial position is held.

* the cone's tilt (option ``operating.cone_tilt``; "locked" by default: the shaft's other support carries
  the moment, and nothing below is evaluated).  "free": the state carries theta = (0, theta_y, theta_z),
  a small rotation of the cone about its reference point (the origin of the geometry's meridional
  coordinates, displaced by d), and its rate; two angles, not a quaternion, because the cone's attitude
  matters only through its axis a = R(theta) e_x (raceway and rib are surfaces of revolution and the
  spin is prescribed), tilts are 1e-5-1e-4 rad (no singularity near) and a quaternion would carry the
  prescribed spin angle and a norm drift for a 2-DOF motion.  R(theta) is the exact rotation of the
  rotation vector (the raceway stays a rigid surface); the equations of motion keep first order in the
  tilt (their second-order terms are 1e-4 of the first at 1e-4 rad).  Each cone slice and the rib are
  evaluated in the cone frame (S_c = R^T (S - d), e_c = R^T e, :func:`slice_contact_3d`, point and normal
  back with R), the cone's surface velocity is v_d + (Omega a + (0, theta_y', theta_z')) x (P - d), the
  guide land's centre moves by R x_L e_x - x_L e_x (x_L its axial station) and its force acts on the axis
  there.  The moments of these forces about the cone's reference point, the radial load's x_F F_r about z
  (F_r acting at ``operating.load_offset`` x_F) and an applied moment drive the tilt (Euler's equations
  of the spinning cone, gyroscopic coupling I_x Omega included: :func:`rhs`).  The cone's mass centre is
  taken at its reference point (its weight makes no moment).

Tilt moment (diagnostics, :data:`lubedyn.dynamics.tapered.layout.TILT_MOMENT_NAMES`): each contact's moment
on roller j about its tilt axis t = e_x x e_r = (0, -c_z, c_y)/|c_yz| through its mass centre c (positive
turns its axis from x towards r, the sense of "Tilt [rad]"), as seven terms -- cup and cone normal loads,
cup and cone traction, flange normal force and friction, cage (pockets and side beams) -- whose sum is
T_j . t.  In the mean a roller orbiting at Omega and spinning at omega_s needs from its contacts the
moment Omega sin(beta) [I_x (omega_s + Omega cos beta) - I_y Omega cos beta] about t (Euler's equations,
beta the axis angle): -0.163 N m at Fig. 5's point, matched by the terms' loaded-zone sum to 0.1 % over
20-40 ms (benchmarks/results/trb_tilt_sign.json).  Which term sets the tilt's sign (docs/paper_a.md, "Which
raceway law gives which tilt sign"):

(a) the raceway normal loads: their distribution along the line makes whatever moment the other terms
    leave; a tilt Delta beta relative to the raceways changes it by -k Delta beta, k = sum (10/9) (q_k/delta_k)
    (u_k - u_c)^2 over both lines' slices (Palmgren) = 3.9e5 N m/rad at the most loaded roller (the runs
    show 3.8e5);
(b) the raceway traction of a skewed roller: skew psi turns the roller's surface velocity at both
    contacts by psi, so the roller slides along its axis at psi u_e relative to the cup one way and to the
    cone the other; the two tractions against that sliding act on opposite sides of the axis (at +-rho
    along the contact normals) and form a couple about t of rho_m [mu_cup(|psi|) Q_cup + mu_cone(|psi|)
    Q_cone] with the sign of psi (kinematics: psi > 0 drags the roller towards -x at the cup and +x at the
    cone, both moments +rho F about t).  The laws differ here only, through mu at a slide-to-roll ratio
    |psi| ~ 1e-2: the limited and map laws are at their limiting shear (0.072 / 0.060-0.063), eq. 12
    ("paper", ambient viscosity) gives 6e-7; measured couple +4.58 / +4.09 / +4.4e-5 N m at skew +8.3 /
    +9.2 / +9.3e-3 rad (limited / map / paper), 0.98 / 1.02 / 1.08 of the closed form;
(c) the flange: its normal force acts on the end sphere towards the small end at a point off the axis on
    the cone's side, a moment -0.85 to -0.97 N m (negative: paper A's tilt sense; what sets the
    quasi-static tilt, -2.2e-6 rad in the loaded zone); its friction adds +0.07 to +0.10 N m.

So the tilt is the quasi-static one plus about (couple + changes of (c))/k: from the nominal axis +1.1e-5
rad with the limited law, -1.0e-6 with eq. 12 (a run in which the rollers are not held: slip -15 %).

Not yet: a rib film that follows the load.  :func:`forces_many` returns slice
loads, contact loads, friction and cage diagnostics at sampled states; the model's ``diagnostics`` reads
tilt, skew and slip from them.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit
from numba import types as nbtypes

from lubedyn.lubrication.laws.cage import guide_land_short_bearing, guide_land_torque, pocket_force, side_beam_force
from lubedyn.lubrication.laws.collision import hertz_force
from lubedyn.lubrication.laws.film import dowson_toyoda_central
from lubedyn.lubrication.laws.jit import INLINE, JIT
from lubedyn.lubrication.laws.flange import flange_friction
from lubedyn.lubrication.laws.slices import slice_contact_3d, slice_force
from lubedyn.lubrication.laws.traction import (elastic_limited, elastic_strip_slope, limited_ellipse_traction,
                                      limited_strip_traction, paper_raceway_traction)

from ..interp import hermite_dot, hermite_value, locate, pair2
from ..integrators import put
from ..specialise import register_kernel, specialise
from ..rotations import euler_rate, quat_derivative, quat_from_rotvec, quat_rotate, quat_rotate_inverse, quat_to_matrix
from .layout import *  # noqa: F401,F403  (option codes and records: lubedyn.dynamics.tapered.layout)
from .layout import (AXIAL_FORCE, F_TILT, L_CONE, L_CUP, L_FLANGE, L_POCKET, LAND_CONTACT, LAND_FILM, N_CAGE_DIAG,
                     N_CONE, N_FRICTION, NB, POCKET_CONTACT, POCKET_FILM, TRACTION_LIMITED, TRACTION_MAP,
                     TRACTION_PAPER)
from .layout import KernelArgs, MapTable, TractionTable  # noqa: F401  (the records the kernels take)

_dowson_toyoda = njit(**INLINE)(dowson_toyoda_central)   # the law of lubedyn.lubrication.laws.film, compiled here


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
def _tilt_about(t1, t2, r0, r1, r2, f0, f1, f2):
    """(r x f).t of a force f at r (from a roller's mass centre) about its tilt axis t = (0, t1, t2)."""
    return t1 * (r2 * f0 - r0 * f2) + t2 * (r0 * f1 - r1 * f0)


@njit(**INLINE)
def _rheo(P):
    """The grease rheology tuple (tau_y, phi0, n, alpha, tau_L0, gamma_L, D_r) of the limited laws."""
    return (P.tauy, P.phi0, P.nexp, P.alphag, P.taul0, P.gammal, P.dr)


@njit(**INLINE)
def _race_radius(race, P):
    """Reduced radius R' [m] of raceway ``race`` (0 cup, 1 cone)."""
    return P.rxo if race == 0 else P.rxi


@njit(**INLINE)
def _race_viscosity(race, P):
    """The viscosity [Pa s] of raceway ``race``'s (0 cup, 1 cone) Dowson-Toyoda film: ``P.etao`` / ``P.etai``
    (the model's :meth:`lubedyn.dynamics.tapered.groups.Lubricant.film_viscosities`: both the films'
    Newtonian viscosity ``P.eta`` unless the scene set them from the grease's EHL film)."""
    return P.etao if race == 0 else P.etai


@njit(**INLINE)
def strip_film(w, race, P):
    """(Hertz half-width b [m], peak pressure p0 [Pa], Dowson-Toyoda central film h0 [m] at the ideal
    entrainment speed) of a strip of raceway ``race`` (0 cup, 1 cone; reduced radius R' and film viscosity
    eta_race) carrying the line load ``w`` [N/m]: b = sqrt(8 w R'/(pi E')), p0 = 2 w/(pi b),
    h0 = R' H_DT(eta_race u_e/(E' R'), alpha E', w/(E' R'))."""
    ep = P.ep
    radius = _race_radius(race, P)
    b = math.sqrt(8.0 * w * radius / (math.pi * ep))
    h0 = radius * _dowson_toyoda(_race_viscosity(race, P) * P.ue / (ep * radius), P.pvc * ep, w / (ep * radius))
    return b, 2.0 * w / (math.pi * b), h0


@njit(**INLINE)
def _slice_film(load, race, P):
    """(line load w [N/m], b, p0, h0) of a slice of raceway ``race`` carrying ``load`` [N]
    (:func:`strip_film` at w = load/width)."""
    w = load / P.width
    b, p0, h0 = strip_film(w, race, P)
    return w, b, p0, h0


@njit(**JIT)
def raceway_film(w, race, P):
    """The Dowson-Toyoda central film [m] the kernel gives a strip of raceway ``race`` (0 cup, 1 cone)
    carrying the line load ``w`` [N/m] (:func:`strip_film`; what sets the limited traction's shear rate
    and the film's elastic slope 2 G b^2/(u_e h))."""
    return strip_film(w, race, P)[2]


@njit(**INLINE)
def _load_cage(Fg, Tg, h0, h1, h2, f0, f1, f2):
    """The reaction of a force (f0, f1, f2) on a roller, acting on the cage at h (from the cage's centre):
    -f added to the cage's force and h x (-f) to its torque."""
    Fg[0] -= f0
    Fg[1] -= f1
    Fg[2] -= f2
    x0, x1, x2 = _cross(h0, h1, h2, -f0, -f1, -f2)
    Tg[0] += x0
    Tg[1] += x1
    Tg[2] += x2


@njit(**INLINE)
def _rot(R, a0, a1, a2):
    """R a (R a 3 x 3 array)."""
    return (R[0, 0] * a0 + R[0, 1] * a1 + R[0, 2] * a2, R[1, 0] * a0 + R[1, 1] * a1 + R[1, 2] * a2,
            R[2, 0] * a0 + R[2, 1] * a1 + R[2, 2] * a2)


@njit(**INLINE)
def _rot_t(R, a0, a1, a2):
    """R^T a (from the inertial frame into the tilted cone's)."""
    return (R[0, 0] * a0 + R[1, 0] * a1 + R[2, 0] * a2, R[0, 1] * a0 + R[1, 1] * a1 + R[2, 1] * a2,
            R[0, 2] * a0 + R[1, 2] * a1 + R[2, 2] * a2)


@njit(**INLINE)
def _load_cone(Fc, Tc, tilted, q0, q1, q2, f0, f1, f2):
    """The reaction of a force (f0, f1, f2) on a roller at q (from the cone's reference point), acting on
    the cone: -f added to Fc and, with the tilt free, q x (-f) to Tc."""
    Fc[0] -= f0
    Fc[1] -= f1
    Fc[2] -= f2
    if tilted:
        t0, t1, t2 = _cross(q0, q1, q2, -f0, -f1, -f2)
        Tc[0] += t0
        Tc[1] += t1
        Tc[2] += t2


@njit(**INLINE)
def _traction_per_speed(load, race, P):
    """Eq. 12's traction per sliding speed [N s/m] of a slice of raceway ``race`` carrying ``load`` [N]:
    pi eps eta sqrt(R'/(2 h0)) times the slice width
    (:func:`lubedyn.lubrication.laws.traction.paper_raceway_traction`); eta the films' Newtonian viscosity
    ``P.eta`` (eq. 12's), h0 the race's film (:func:`_slice_film`, its own film viscosity)."""
    w, b, p0, h0 = _slice_film(load, race, P)
    return paper_raceway_traction(1.0, P.eta, _race_radius(race, P), h0, b) * P.width


@njit(**JIT)
def strip_viscous_traction(w, race, vs, P):
    """The limited Herschel-Bulkley traction per unit length [N/m] of a strip of raceway ``race`` (0 cup,
    1 cone) carrying the line load ``w`` [N/m] and sliding at ``vs`` [m/s]
    (:func:`lubedyn.lubrication.laws.traction.limited_strip_traction` over the Hertz strip of :func:`_slice_film`,
    Gauss rule), before the film's elastic shear: the function the traction tables hold."""
    b, p0, h0 = strip_film(w, race, P)
    return limited_strip_traction(vs, h0, b, p0, _rheo(P))


@njit(**JIT)
def strip_viscous_table(V, W, race, P):
    """:func:`strip_viscous_traction` of raceway ``race`` at every (V[i], W[j]): the values of a traction table."""
    out = np.empty((V.size, W.size))
    for i in range(V.size):
        for j in range(W.size):
            out[i, j] = strip_viscous_traction(W[j], race, V[i], P)
    return out


@njit(**INLINE)
def _table_viscous(race, w, vs, table, counter):
    """The viscous part of the limited traction per unit length [N/m] from raceway ``race``'s table (cubic
    Hermite in log v_s and log w of the logarithm of the values, ``table``: :class:`TractionTable`), or -1 when (v_s, w) lies outside it
    (the caller then evaluates the law)."""
    # lubedyn.dynamics.interp.hermite2's operations in the same order, inlined (its call with array views cost
    # about as much as the interpolation); without its fused multiply-adds, so equal to round-off only: a
    # 10 ms run of Fig. 5's point moves by 1.5e-8 relative at most
    av, aw = table.speeds[race], table.loads[race]
    i, c0, o0 = locate(av, math.log(vs))
    j, c1, o1 = locate(aw, math.log(w))
    if o0 != 0 or o1 != 0:
        return -1.0
    D = table.data[race]
    w1 = hermite_value(aw, j, c1)
    return math.exp(hermite_dot(pair2(D, 0, i, j, w1), pair2(D, 1, i, j, w1), hermite_value(av, i, c0)))


@njit(**JIT)
def map_traction_coefficient(race, w, s, P, maps, counter):
    """Traction coefficient [-] of raceway ``race`` (0 cup, 1 cone) at line load ``w`` [N/m] and
    slide-to-roll ratio ``s`` >= 0 from the roller EHL map's tables at the run's entrainment speed
    (``maps``, :class:`MapTable`: :meth:`lubedyn.dynamics.tapered.model.TaperedBearing.map_traction_tables`), read as the map reads its sheared
    traction (:class:`lubedyn.maps.FilmMap`, "sheared"): the transition slip s_t(w) (cubic Hermite in
    log w of log s_t), the normalised slip sigma = s/s_t, the map's coordinate x = centre exp(asinh(ln
    sigma / a)/b) (clamped to the axis), and G(w, x) (cubic Hermite in log w, log x of log G).  Worked in
    the logarithms throughout (ln x = ln centre + asinh((ln s - ln s_t)/a)/b; one cell search and one set of
    Hermite weights in log w for both tables): the map's values to round-off with two transcendental
    functions fewer than the generic readers (lubedyn.dynamics.interp.hermite1/hermite2) would take.  Below the
    slide-to-roll axis' first node the traction is linear in s (the maps' convention: the film's shear is
    linear there); above its last node it is held; a load outside the axis is clamped (counted in
    ``counter[0]``)."""
    aw = maps.loads[race]
    ax = maps.slips[race]
    st = maps.shift[race]
    scale = 1.0
    lo = P.tmslo
    if s < lo:
        scale = s / lo
        s = lo
    elif s > P.tmshi:
        s = P.tmshi
    i, tw, out = locate(aw, math.log(w))
    counter[0] += out
    bw = hermite_value(aw, i, tw)
    ln_st = (bw[0] * st[0, i] + bw[1] * st[0, i + 1]) + (bw[2] * st[1, i] + bw[3] * st[1, i + 1])
    j, tx, _ = locate(ax, math.log(P.tmcen) + math.asinh((math.log(s) - ln_st) / P.tma) / P.tmb)
    wx = hermite_value(ax, j, tx)
    G = maps.values[race]
    return scale * math.exp(hermite_dot(pair2(G, 0, i, j, wx), pair2(G, 1, i, j, wx), bw))


@njit(**INLINE)
def slice_traction(load, race, vs, P, table, maps, counter):
    """Magnitude [N] of the raceway traction of a slice of raceway ``race`` (0 cup, 1 cone) sliding at
    ``vs`` >= 0 [m/s] (the force opposes the roller's sliding): eq. 12 ("paper"), the limited
    Herschel-Bulkley strip law ("limited", :func:`strip_viscous_traction`, from the raceway's table when
    the model has tables and (v_s, w) lies inside) in series with the film's elastic shear
    (:func:`lubedyn.lubrication.laws.traction.elastic_limited`, shear modulus G), or the roller EHL map's
    traction coefficient times the slice load ("map", :func:`map_traction_coefficient`, at the slide-to-roll
    ratio v_s/u_e of the run's ideal entrainment speed)."""
    if P.traction == TRACTION_PAPER:
        return _traction_per_speed(load, race, P) * vs
    if vs <= 0.0:
        return 0.0
    if P.traction == TRACTION_MAP:  # the EHL map's film traction (its elastic shear included)
        return map_traction_coefficient(race, load / P.width, vs / P.ue, P, maps, counter) * load
    w, b, p0, h0 = _slice_film(load, race, P)
    viscous = -1.0
    if P.ttab != 0.0:
        viscous = _table_viscous(race, w, vs, table, counter)
    if viscous < 0.0:
        viscous = limited_strip_traction(vs, h0, b, p0, _rheo(P))
    return elastic_limited(viscous * P.width, elastic_strip_slope(P.gshear, b, P.ue, h0) * P.width, vs)


@njit(**JIT)
def contact_forces(y, A, F, T, Fc, Tc, loads, Fg, Tg, SL, FR, CG):
    """Contact forces and torques: F[j] force on roller j [N], T[j] torque about its mass centre
    (inertial frame) [N m], Fc the force of all rollers (and the cage) on the cone [N], Tc their moment
    about the cone's (displaced) reference point [N m] (computed with the cone's tilt free; zeros when it
    is locked, which keeps the locked path's cost), loads[j] =
    (cup, cone, flange, pocket) sums of the normal forces' magnitudes [N]; Fg, Tg the force [N] and the
    torque about its centre [N m] on the cage; SL[j, race, k] the slice loads [N] (race 0 cup, 1 cone);
    FR[j] the friction diagnostics (:data:`lubedyn.dynamics.tapered.layout.FRICTION_NAMES`: friction forces,
    sliding speeds and the terms of the tilt moment, module docstring); CG the cage's
    (:data:`lubedyn.dynamics.tapered.layout.CAGE_NAMES`).  ``A``: the model's :class:`KernelArgs`."""
    P, U, RHO = A.P[0], A.U, A.RHO
    Z = int(P.z)
    ns = int(P.ns)
    F[:, :] = 0.0
    T[:, :] = 0.0
    Fc[:] = 0.0
    Tc[:] = 0.0
    Fg[:] = 0.0
    Tg[:] = 0.0
    loads[:, :] = 0.0
    SL[:, :, :] = 0.0
    FR[:, :] = 0.0
    CG[:] = 0.0
    if P.contacts == 0.0:
        return
    counter = np.zeros(1, dtype=np.int64)      # queries outside a traction table (lubedyn.dynamics.interp)
    dx, dy, dz = y[0], y[1], y[2]
    vcx, vcy, vcz = y[3], y[4], y[5]
    om = P.omega
    # the cone's angular velocity and attitude: the prescribed spin Omega about its axis a = R e_x and,
    # tilted, the tilt rate (0, theta_y', theta_z'); R the rotation of the rotation vector (0, theta_y,
    # theta_z) (used only when the tilt is free)
    tilted = P.tilt != 0.0
    wx, wy, wz = om, 0.0, 0.0
    lx, ly, lvx, lvy = 0.0, 0.0, 0.0, 0.0
    Rm = np.empty((3, 3))
    if tilted:
        kt = int(P.tiltat)
        qt = np.empty(4)
        quat_from_rotvec(np.array([0.0, y[kt], y[kt + 1]]), qt)
        quat_to_matrix(qt, Rm)
        wx, wy, wz = om * Rm[0, 0], om * Rm[1, 0] + y[kt + 2], om * Rm[2, 0] + y[kt + 3]
        # the guide land's centre and velocity (y, z) at its axial station x_L, moved by the tilt
        xl = P.landx
        lx, ly = xl * Rm[1, 0], xl * Rm[2, 0]
        lvx, lvy = xl * y[kt + 3], -xl * y[kt + 2]
    ex_b = np.array([1.0, 0.0, 0.0])
    e = np.empty(3)
    wi = np.empty(3)
    # the cage's attitude (unit quaternion) and inertial angular velocity, once for all its contacts
    bc = N_CONE + Z * NB
    qc = np.empty(4)
    wc = np.zeros(3)
    if P.cage != 0.0:
        qn = math.sqrt(y[bc + 3] ** 2 + y[bc + 4] ** 2 + y[bc + 5] ** 2 + y[bc + 6] ** 2)
        for i in range(4):  # a loop, not qc[:] = ...: see lubedyn.dynamics.integrators.put
            qc[i] = y[bc + 3 + i] / qn
        quat_rotate(qc, y[bc + 10:bc + 13], wc)
    for j in range(Z):
        b = N_CONE + j * NB
        c0, c1, c2 = y[b], y[b + 1], y[b + 2]
        q = y[b + 3:b + 7] / math.sqrt(y[b + 3] ** 2 + y[b + 4] ** 2 + y[b + 5] ** 2 + y[b + 6] ** 2)
        v0, v1, v2 = y[b + 7], y[b + 8], y[b + 9]
        quat_rotate(q, ex_b, e)
        quat_rotate(q, y[b + 10:b + 13], wi)          # angular velocity, inertial frame
        e0, e1, e2 = e[0], e[1], e[2]
        # the roller's tilt axis t = e_x x e_r = (0, -c_z, c_y)/|c_yz| (the diagnostics' tilt moments)
        rc = math.sqrt(c1 * c1 + c2 * c2)
        ta1, ta2 = -c2 / rc, c1 / rc
        # the roller's mid-point (slice coordinates u are measured from it)
        m0, m1, m2 = c0 - P.uc * e0, c1 - P.uc * e1, c2 - P.uc * e2
        for race in range(2):
            if race == 0:
                px, pr, nx, nr = P.cupx, P.cupr, P.cupnx, P.cupnr
                ox, oy, oz = 0.0, 0.0, 0.0
            else:
                px, pr, nx, nr = P.conx, P.conr, P.connx, P.connr
                ox, oy, oz = dx, dy, dz
            for k in range(ns):
                u = U[k]
                s0, s1, s2 = m0 + u * e0 - ox, m1 + u * e1 - oy, m2 + u * e2 - oz
                if race == 1 and tilted:
                    # the cone's raceway is a surface of revolution about its own axis: the slice in the
                    # cone frame (R^T), the contact point and normal back (R)
                    t0, t1, t2 = _rot_t(Rm, s0, s1, s2)
                    a0, a1, a2 = _rot_t(Rm, e0, e1, e2)
                    delta, c0_, c1_, c2_, k0_, k1_, k2_ = slice_contact_3d(t0, t1, t2, a0, a1, a2, RHO[k], px, pr, nx, nr)
                    if delta <= 0.0:
                        continue
                    q0, q1, q2 = _rot(Rm, c0_, c1_, c2_)
                    n0, n1, n2 = _rot(Rm, k0_, k1_, k2_)
                else:
                    delta, q0, q1, q2, n0, n1, n2 = slice_contact_3d(s0, s1, s2, e0, e1, e2, RHO[k], px, pr, nx, nr)
                if delta <= 0.0:
                    continue
                P0, P1, P2 = q0 + ox, q1 + oy, q2 + oz     # contact point, inertial
                r0, r1, r2 = P0 - c0, P1 - c1, P2 - c2
                w0, w1, w2 = _cross(wi[0], wi[1], wi[2], r0, r1, r2)
                u0, u1, u2 = v0 + w0, v1 + w1, v2 + w2     # roller surface velocity at P
                if race == 1:                               # cone surface: v_d + w_cone x (P - d)
                    a0, a1, a2 = _cross(wx, wy, wz, q0, q1, q2)
                    u0 -= vcx + a0
                    u1 -= vcy + a1
                    u2 -= vcz + a2
                ddot = -(u0 * n0 + u1 * n1 + u2 * n2)
                f = slice_force(delta, ddot, P.kw, P.alpha)
                if f <= 0.0:
                    continue
                f0, f1, f2 = f * n0, f * n1, f * n2
                FR[j, F_TILT + race] += _tilt_about(ta1, ta2, r0, r1, r2, f0, f1, f2)
                if P.traction != 0.0:
                    # against the sliding velocity's tangential part: rolling direction and the axial
                    # sliding a skewed roller makes, one vector
                    un = u0 * n0 + u1 * n1 + u2 * n2
                    s0, s1, s2 = u0 - un * n0, u1 - un * n1, u2 - un * n2
                    vs = math.sqrt(s0 * s0 + s1 * s1 + s2 * s2)
                    if vs > 0.0:
                        ft = slice_traction(f, race, vs, P, A.table, A.maps, counter)
                        g0, g1, g2 = -ft * s0 / vs, -ft * s1 / vs, -ft * s2 / vs
                        f0 += g0
                        f1 += g1
                        f2 += g2
                        FR[j, race] += ft
                        FR[j, F_TILT + 2 + race] += _tilt_about(ta1, ta2, r0, r1, r2, g0, g1, g2)
                        if vs > FR[j, 4 + race]:
                            FR[j, 4 + race] = vs
                _load_roller(F, T, j, r0, r1, r2, f0, f1, f2)
                loads[j, race] += f
                SL[j, race, k] = f
                if race == 1:
                    _load_cone(Fc, Tc, tilted, q0, q1, q2, f0, f1, f2)
        # flange: the large-end sphere against the rib (on the cone)
        us = P.us
        s0, s1, s2 = m0 + us * e0 - dx, m1 + us * e1 - dy, m2 + us * e2 - dz
        if tilted:      # the rib in the cone frame, its normal back
            t0, t1, t2 = _rot_t(Rm, s0, s1, s2)
            a0, a1, a2 = _rot_t(Rm, e0, e1, e2)
            d0, _, _, _, k0_, k1_, k2_ = slice_contact_3d(t0, t1, t2, a0, a1, a2, 0.0, P.flx, P.flr, P.flnx,
                                                          P.flnr)
            n0, n1, n2 = _rot(Rm, k0_, k1_, k2_)
        else:
            d0, _, _, _, n0, n1, n2 = slice_contact_3d(s0, s1, s2, e0, e1, e2, 0.0, P.flx, P.flr,
                                                       P.flnx, P.flnr)
        delta = P.rs + d0
        if delta > 0.0:
            q0, q1, q2 = s0 - P.rs * n0, s1 - P.rs * n1, s2 - P.rs * n2
            P0, P1, P2 = q0 + dx, q1 + dy, q2 + dz
            r0, r1, r2 = P0 - c0, P1 - c1, P2 - c2
            w0, w1, w2 = _cross(wi[0], wi[1], wi[2], r0, r1, r2)
            a0, a1, a2 = _cross(wx, wy, wz, q0, q1, q2)
            u0, u1, u2 = v0 + w0 - vcx - a0, v1 + w1 - vcy - a1, v2 + w2 - vcz - a2
            un = u0 * n0 + u1 * n1 + u2 * n2
            f = hertz_force(delta, -un, P.kf, P.alpha)
            if f > 0.0:
                f0, f1, f2 = f * n0, f * n1, f * n2
                FR[j, F_TILT + 4] = _tilt_about(ta1, ta2, r0, r1, r2, f0, f1, f2)
                if P.ffric != 0.0:
                    s0, s1, s2 = u0 - un * n0, u1 - un * n1, u2 - un * n2
                    vs = math.sqrt(s0 * s0 + s1 * s1 + s2 * s2)
                    FR[j, 6] = vs
                    if vs > 0.0:
                        c3 = f ** (1.0 / 3.0)          # Hertz: a, b, p0 scale with Q^(1/3)
                        grease = limited_ellipse_traction(vs, P.hrib, P.fa1 * c3, P.fb1 * c3,
                                                          P.fp01 * c3, _rheo(P))
                        ff = flange_friction(vs, f, P.lam, grease, P.mua, P.fbc, P.fcc,
                                             P.ffric == 2.0)
                        g0, g1, g2 = -ff * s0 / vs, -ff * s1 / vs, -ff * s2 / vs
                        f0 += g0
                        f1 += g1
                        f2 += g2
                        FR[j, 2] = ff
                        FR[j, F_TILT + 5] = _tilt_about(ta1, ta2, r0, r1, r2, g0, g1, g2)
                _load_roller(F, T, j, r0, r1, r2, f0, f1, f2)
                loads[j, 2] += f
                _load_cone(Fc, Tc, tilted, q0, q1, q2, f0, f1, f2)
        if P.cage != 0.0:
            x1, x2 = T[j, 1], T[j, 2]          # the pockets' and side beams' tilt moment: T's change
            _pocket(j, y, P, qc, wc, c0, c1, c2, v0, v1, v2, wi, e0, e1, e2, m0, m1, m2, F, T, loads, Fg, Tg, FR)
            if P.sidegap > 0.0:
                _side_beams(j, y, P, qc, wc, c0, c1, c2, v0, v1, v2, wi, e0, e1, e2, m0, m1, m2, F, T, Fg, Tg, CG)
            FR[j, F_TILT + 6] = ta1 * (T[j, 1] - x1) + ta2 * (T[j, 2] - x2)
    if P.cage != 0.0:
        fy0, fz0 = Fc[1], Fc[2]
        _guide_land(y, P, wc, Fc, Fg, Tg, CG, lx, ly, lvx, lvy)
        if tilted:      # the land's force acts on the cone's axis at the land's station x_L
            Tc[1] -= P.landx * (Fc[2] - fz0)
            Tc[2] += P.landx * (Fc[1] - fy0)
        CG[0], CG[1], CG[2] = Fg[1], Fg[2], Tg[0]


@njit(**INLINE)
def _pocket(j, y, P, qc, wc, c0, c1, c2, v0, v1, v2, wi, e0, e1, e2, m0, m1, m2, F, T, loads, Fg, Tg, FR):
    """Roller j against the crossbeams of its pocket (module docstring): forces on the roller and the cage
    (``qc`` the cage's unit quaternion, ``wc`` its inertial angular velocity)."""
    Z = int(P.z)
    b = N_CONE + Z * NB
    g0, g1, g2 = y[b], y[b + 1], y[b + 2]
    phi = 2.0 * math.pi * j / Z
    tb = np.array([0.0, -math.sin(phi), math.cos(phi)])
    t = np.empty(3)
    quat_rotate(qc, tb, t)                        # the pocket's circumferential unit vector, inertial
    s = t[0] * (m0 - g0) + t[1] * (m1 - g1) + t[2] * (m2 - g2)
    for side in range(2):
        sg = 1.0 if side == 0 else -1.0           # leading beam (+t), trailing beam (-t)
        gap = P.pocket - sg * s
        if P.pocketmode == POCKET_CONTACT and gap >= 0.0:
            continue
        # contact point on the roller's side facing the beam
        p0, p1, p2 = m0 + sg * P.rhom * t[0], m1 + sg * P.rhom * t[1], m2 + sg * P.rhom * t[2]
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
        if P.pocketmode == POCKET_FILM:
            q, f = pocket_force(gap, -sg * un, vs, P.rhom, P.len, P.eta, P.hcrit, P.kh, P.ch,
                                P.mubd, int(P.switch))
        else:   # "contact": line contact of the roller on the beam (Palmgren law, eq. 11 damping), mu_bd
            q = slice_force(-gap, sg * un, P.kpocket, P.alpha)
            f = P.mubd * q * math.tanh(vs / P.vreg)
        if q <= 0.0 and f == 0.0:
            continue
        f0, f1, f2 = -sg * q * t[0], -sg * q * t[1], -sg * q * t[2]
        if vs > 0.0:
            f0 -= f * s0 / vs
            f1 -= f * s1 / vs
            f2 -= f * s2 / vs
        _load_roller(F, T, j, r0, r1, r2, f0, f1, f2)
        loads[j, 3] += q
        FR[j, 3] += f
        _load_cage(Fg, Tg, h0, h1, h2, f0, f1, f2)


@njit(**INLINE)
def _side_beams(j, y, P, qc, wc, c0, c1, c2, v0, v1, v2, wi, e0, e1, e2, m0, m1, m2, F, T, Fg, Tg, CG):
    """Roller j's ends against its pocket's side beams (eqs. 39-40): the pocket's centre C_j and axis a_j
    (the roller's nominal axis) ride with the cage; the roller's mid-point M is off C_j along a_j by
    s = a_j.(M - C_j), so the large end's gap is Delta' - s and the small end's Delta' + s.  Film pocket:
    :func:`lubedyn.lubrication.laws.cage.side_beam_force` (squeeze of the end's strip across the beam's thickness,
    boundary state below the critical film); contact-only pocket: a line contact (the pocket's constant,
    eq. 11's damping) once the gap closes.  The force acts along a_j at the end face's centre, on the roller
    and (opposite) on the cage."""
    Z = int(P.z)
    b = N_CONE + Z * NB
    g0, g1, g2 = y[b], y[b + 1], y[b + 2]
    phi = 2.0 * math.pi * j / Z
    cp, sp = math.cos(phi), math.sin(phi)
    cb, sb = math.cos(P.beta0), math.sin(P.beta0)
    cw = np.empty(3)
    quat_rotate(qc, np.array([P.pockx, P.pitch * cp, P.pitch * sp]), cw)
    a = np.empty(3)
    quat_rotate(qc, np.array([cb, sb * cp, sb * sp]), a)
    s = a[0] * (m0 - g0 - cw[0]) + a[1] * (m1 - g1 - cw[1]) + a[2] * (m2 - g2 - cw[2])
    half = 0.5 * P.len
    for end in range(2):
        sg = 1.0 if end == 0 else -1.0            # large end (+a), small end (-a)
        gap = P.sidegap - sg * s
        if P.pocketmode == POCKET_CONTACT and gap >= 0.0:
            continue
        p0, p1, p2 = m0 + sg * half * e0, m1 + sg * half * e1, m2 + sg * half * e2   # end face centre
        r0, r1, r2 = p0 - c0, p1 - c1, p2 - c2
        w0, w1, w2 = _cross(wi[0], wi[1], wi[2], r0, r1, r2)
        h0, h1, h2 = p0 - g0, p1 - g1, p2 - g2
        k0, k1, k2 = _cross(wc[0], wc[1], wc[2], h0, h1, h2)
        rel = (a[0] * (v0 + w0 - y[b + 7] - k0) + a[1] * (v1 + w1 - y[b + 8] - k1)
               + a[2] * (v2 + w2 - y[b + 9] - k2))
        rate = -sg * rel                           # d(gap)/dt
        if P.pocketmode == POCKET_FILM:
            d = P.dlarge if end == 0 else P.dsmall
            f = side_beam_force(gap, rate, d, P.hside, P.eta, P.hcrit, P.kh, P.ch)
        else:
            f = slice_force(-gap, -rate, P.kpocket, P.alpha)
        if f <= 0.0:
            continue
        f0, f1, f2 = -sg * f * a[0], -sg * f * a[1], -sg * f * a[2]
        _load_roller(F, T, j, r0, r1, r2, f0, f1, f2)
        _load_cage(Fg, Tg, h0, h1, h2, f0, f1, f2)
        CG[4] += f


@njit(**INLINE)
def _guide_land(y, P, wc, Fc, Fg, Tg, CG, lx, ly, lvx, lvy):
    """The cage's centering surface on the cone's guide land (module docstring); (lx, ly) and (lvx, lvy)
    move the land's centre and velocity (y, z) off the cone's (the tilt; 0 when locked)."""
    Z = int(P.z)
    b = N_CONE + Z * NB
    # the land (journal) relative to the cage (bearing), in the radial plane (y, z)
    ex, ey = y[1] + lx - y[b + 1], y[2] + ly - y[b + 2]
    vx, vy = y[4] + lvx - y[b + 8], y[5] + lvy - y[b + 9]
    r, c, w = P.rland, P.cland, P.bland
    ecc = math.sqrt(ex * ex + ey * ey)
    fx, fy, torque = 0.0, 0.0, 0.0
    slide = r * (P.omega - wc[0])
    if P.landmode == LAND_FILM:
        ecc_f = ecc if ecc < c else c * (1.0 - 1e-9)
        fx, fy = guide_land_short_bearing(ex, ey, vx, vy, r, c, w, P.eta, r * (P.omega + wc[0]))
        torque = guide_land_torque(ecc_f / c, r, c, w, P.eta, P.omega, wc[0])
        gap = c - ecc
        if gap < P.hland and ecc > 0.0:
            nx, ny = ex / ecc, ey / ecc                 # from the cage's centre towards the land's
            vr = vx * nx + vy * ny                       # rate at which the land closes on the bore
            qs = P.kh * (P.hland - gap) + P.ch * vr
            if qs > 0.0:
                # the bore pushes the land back towards the cage's centre (-n; the first step had +n)
                fx -= qs * nx
                fy -= qs * ny
                torque += P.mubd * qs * r * (1.0 if slide > 0.0 else (-1.0 if slide < 0.0 else 0.0))
                CG[3] = qs
    elif P.landmode == LAND_CONTACT and ecc > c:
        # contact only: the land touches the cage's bore (line contact of the land's width, Palmgren law with
        # eq. 11 damping), friction mu_bd along the land's sliding (regularised Coulomb)
        nx, ny = ex / ecc, ey / ecc
        qs = slice_force(ecc - c, vx * nx + vy * ny, P.kland, P.alpha)
        fx -= qs * nx
        fy -= qs * ny
        torque = P.mubd * qs * r * math.tanh(slide / P.vreg)
        CG[3] = qs
    # (fx, fy) acts on the land (journal): the cage gets the opposite, the cone the force itself
    Fg[1] -= fx
    Fg[2] -= fy
    Fc[1] += fx
    Fc[2] += fy
    Tg[0] += torque


@njit(**JIT)
def rhs(t, y, args, dydt):
    """dy/dt of the tapered roller bearing (module docstring); ``args``: the model's :class:`KernelArgs`."""
    P = args.P[0]
    Z = int(P.z)
    ns = int(P.ns)
    F = np.empty((Z, 3))
    T = np.empty((Z, 3))
    Fc = np.empty(3)
    Tc = np.empty(3)
    loads = np.empty((Z, 4))
    Fg = np.empty(3)
    Tg = np.empty(3)
    SL = np.empty((Z, 2, ns))
    FR = np.empty((Z, N_FRICTION))
    CG = np.empty(N_CAGE_DIAG)
    contact_forces(y, args, F, T, Fc, Tc, loads, Fg, Tg, SL, FR, CG)
    g = P.grav                                      # gravity along -y
    # cone: translation under the rollers' forces, F_r along +y, F_a along -x (closing the bearing)
    mc = P.mc
    dydt[0] = y[3]
    dydt[1] = y[4]
    dydt[2] = y[5]
    if P.axial == AXIAL_FORCE:
        dydt[3] = (Fc[0] - P.fa) / mc
    else:
        dydt[0] = 0.0
        dydt[3] = 0.0
    dydt[4] = (Fc[1] + P.fr) / mc - g
    dydt[5] = Fc[2] / mc
    inertia = np.array([P.ix, P.iy, P.iy])
    tb = np.empty(3)
    m = P.m
    for j in range(Z):
        b = N_CONE + j * NB
        q = y[b + 3:b + 7]
        dydt[b] = y[b + 7]
        dydt[b + 1] = y[b + 8]
        dydt[b + 2] = y[b + 9]
        quat_derivative(q, y[b + 10:b + 13], dydt[b + 3:b + 7], P.qstab)
        dydt[b + 7] = F[j, 0] / m
        dydt[b + 8] = F[j, 1] / m - g
        dydt[b + 9] = F[j, 2] / m
        qn = q / math.sqrt(q[0] ** 2 + q[1] ** 2 + q[2] ** 2 + q[3] ** 2)
        quat_rotate_inverse(qn, T[j], tb)
        euler_rate(inertia, y[b + 10:b + 13], tb, dydt[b + 10:b + 13])
    if P.cage != 0.0:
        b = N_CONE + Z * NB
        q = y[b + 3:b + 7]
        free = P.sidegap > 0.0                      # the side beams hold it axially; else held
        dydt[b] = y[b + 7] if free else 0.0
        dydt[b + 1] = y[b + 8]
        dydt[b + 2] = y[b + 9]
        quat_derivative(q, y[b + 10:b + 13], dydt[b + 3:b + 7], P.qstab)
        dydt[b + 7] = Fg[0] / P.mcg if free else 0.0
        dydt[b + 8] = Fg[1] / P.mcg - g
        dydt[b + 9] = Fg[2] / P.mcg
        qn = q / math.sqrt(q[0] ** 2 + q[1] ** 2 + q[2] ** 2 + q[3] ** 2)
        quat_rotate_inverse(qn, Tg, tb)
        euler_rate(np.array([P.icx, P.ict, P.ict]), y[b + 10:b + 13], tb, dydt[b + 10:b + 13])
    if P.tilt != 0.0:
        # the cone's tilt (small rotations theta_y, theta_z about its reference point): Euler's equations
        # of the spinning cone, H = I_x Omega a + I_t (0, theta_y', theta_z'), dH/dt = M with
        # a' = (0, theta_z', -theta_y') (first order in the tilt):
        #   I_t theta_y'' = M_y - I_x Omega theta_z',   I_t theta_z'' = M_z + I_x Omega theta_y'
        # M: the contacts' moment Tc, the radial load's x_F F_r about z and the applied moment
        k = int(P.tiltat)
        gyro = P.iconex * P.omega
        dydt[k] = y[k + 2]
        dydt[k + 1] = y[k + 3]
        dydt[k + 2] = (Tc[1] + P.my - gyro * y[k + 3]) / P.iconet
        dydt[k + 3] = (Tc[2] + P.mz + P.loadx * P.fr + gyro * y[k + 2]) / P.iconet


@njit(**JIT)
def loads_many(Y, args):
    """(n, Z, 4) cup, cone, flange and pocket loads [N] of each roller at each sampled state."""
    P = args.P[0]
    Z = int(P.z)
    out = np.empty((Y.shape[0], Z, 4))
    F = np.empty((Z, 3))
    T = np.empty((Z, 3))
    Fc = np.empty(3)
    Tc = np.empty(3)
    Fg = np.empty(3)
    Tg = np.empty(3)
    SL = np.empty((Z, 2, int(P.ns)))
    FR = np.empty((Z, N_FRICTION))
    CG = np.empty(N_CAGE_DIAG)
    for i in range(Y.shape[0]):
        contact_forces(Y[i], args, F, T, Fc, Tc, out[i], Fg, Tg, SL, FR, CG)
    return out


def _forces_many_impl(contact, Y, args):
    P = args.P[0]
    Z = int(P.z)
    ns = int(P.ns)
    n = Y.shape[0]
    loads = np.empty((n, Z, 4))
    SL = np.empty((n, Z, 2, ns))
    FR = np.empty((n, Z, N_FRICTION))
    CG = np.empty((n, N_CAGE_DIAG))
    FC = np.empty((n, 6))
    F = np.empty((Z, 3))
    T = np.empty((Z, 3))
    Fc = np.empty(3)
    Tc = np.empty(3)
    Fg = np.empty(3)
    Tg = np.empty(3)
    for i in range(n):
        contact(Y[i], args, F, T, Fc, Tc, loads[i], Fg, Tg, SL[i], FR[i], CG[i])
        put(FC[i], 0, Fc)
        put(FC[i], 3, Tc)
    return loads, SL, FR, CG, FC


def _contact_signature(types):
    """:func:`contact_forces` as :func:`_forces_many_impl` calls it (rows of C-contiguous arrays)."""
    v, m = nbtypes.float64[::1], nbtypes.float64[:, ::1]
    return nbtypes.void(v, types["args"], m, m, v, v, m, v, v, nbtypes.float64[:, :, ::1], m, v)


# contact_forces reached through a function pointer (lubedyn.dynamics.specialise): compiled once, not linked and
# re-optimised a second time into this loop
register_kernel(_forces_many_impl, contact=_contact_signature)


def forces_many_example(args):
    """``(kernel, example arguments)`` of :func:`forces_many` (:func:`lubedyn.dynamics.specialise.compile_in_background`)."""
    return specialise(_forces_many_impl, contact=contact_forces), (np.zeros((1, 1)), args)


def forces_many(Y, args):
    """At each sampled state: loads (n, Z, 4) as :func:`loads_many`, slice loads (n, Z, 2, n_s) [N] (cup,
    cone), friction diagnostics (n, Z, N_FRICTION), cage diagnostics (n, N_CAGE_DIAG) and the force [N]
    of the rollers and the cage on the cone and, with the cone's tilt free, their moment about its
    reference point [N m] (n, 6: force x, y, z, moment x, y, z; the moment 0 when the tilt is locked)."""
    return specialise(_forces_many_impl, contact=contact_forces)(np.ascontiguousarray(Y, dtype=np.float64), args)

