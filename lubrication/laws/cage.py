r"""Cage laws of paper A's tapered roller bearing (Wu, Xu & Deng 2018, eqs. 30-46, rebuilt): the roller
slice against the pocket crossbeam, the roller end against the side beam, and the cage's centering
surface on the inner-ring guide land.

Roller slice / crossbeam (eqs. 33-38)
-------------------------------------
The slice (radius R, length l) faces the flat crossbeam across the gap delta (eq. 33: the initial
clearance (l_c - d_w)/2 less the roller's displacement towards the beam).  The roller surface slides
past the beam at the full rolling speed (the beam turns with the cage), so the film is a rigid
cylinder over a plane with the mean surface speed u_m = u/2.  Film state (delta >= dh0, eq. 34):

    q_film = c_M eta u_m R l / h + C_sq(h) v,      c_M = 4.89497 (Martin 1916, Reynolds exit)
    C_sq = 3 sqrt(2) pi eta l R^(3/2) / h^(3/2)  while approaching (v = -d delta/dt > 0), 0 separating
    f_film = (3 pi / sqrt(2)) eta u l sqrt(R/h)                                   (traction, eq. 34)

with h = max(delta, dh0).  What was rebuilt: eq. 34 writes q = k_e delta + c_e d(delta)/dt with
k_e = d f(h0)/d h0 and f(h0) (eq. 35) a Herschel-Bulkley film law whose constants xi_1, xi_2 come
from a reference the extracted text lost ([17]); its exponents (h0^(6n+2), E'') are not recoverable.
For any load law f ~ 1/h, |k_e| h = f, so eq. 34's first term is the film load itself; the
Newtonian f is Martin's rigid-cylinder load, used here with the viscosity the caller chooses (the
grease's base oil, or its apparent Herschel-Bulkley viscosity at the shear rate u/h:
:func:`lubrication.laws.grease` readings).  Eq. 34's damping c_e = 6 pi eps phi0 l_e varsigma^(3/2)
/ (sqrt(2) n_s h0^(3/2)) is exactly the squeeze film of a rigid cylinder approaching a plane with a
full film (p = 6 eta v R/h^2, integrated: 3 sqrt(2) pi eta v R^(3/2)/h^(3/2) per unit length) with
eps = 1, varsigma = R, l = l_e/n_s; during separation the film cavitates (half-Sommerfeld) and the
squeeze force is 0.  The traction is eq. 34's as printed (eps = 1): 3/2 of the Couette shear
eta u pi sqrt(2R/h) of the whole uncavitated film, measured 9.3 % above the project's FEM shear on
the sliding roller over a Reynolds-cavitated film (tests/test_laws_cage.py).

Boundary state (delta < dh0, eqs. 36-37): the solids are deformed by delta_h = dh0 - delta and

    paper:      q = k_h delta_h + c_h d(delta_h)/dt + q_film(dh0),  f = mu_bd q + f_film(dh0)
    continuous: q = k_h delta_h + c_h min(delta_h/dh0, 1) d(delta_h)/dt (>= 0) + q_film(dh0),
                f = mu_bd (q - q_film(dh0)) + f_film(dh0)

The paper's switch jumps at delta = dh0 (its damping force c_h d(delta_h)/dt and the boundary
friction mu_bd q_film appear at once); the continuous switch (default) ramps the damping in with the
deformation and applies mu_bd to the solids' share only, so force and friction are continuous in
delta: an adaptive integrator does not have to resolve a jump at every pocket contact.

Roller end / side beam (eqs. 39-40)
-----------------------------------
The roller end (diameter d: large end when it approaches, small end for the other beam) faces the
side beam of thickness h_s across h_a.  The printed eq. 40 is k_s = -d/dh_a [d phi0 h_s^3/h_a^3
dr_a/dt]: the squeeze film of two parallel plane strips (flow across the beam's thickness w = h_s,
strip length d), W = eta d h_s^3 v / h_a^3 while approaching, 0 separating (Hamrock, Schmid &
Jacobson 2004, sec. 15.2: parallel-surface squeeze film, infinitely long strip), used as the force
itself (eq. 39's q_s = k_s (dd' - r_a) is, like eq. 34, the load of a law written as stiffness x gap).

Guide land (eqs. 43-46)
-----------------------
The cage's centering surface (radius r_y, the "bearing") rides on the inner ring's guide land
(radius r_d, the "journal"), radial clearance c = r_y - r_d (Table 1's 0.5 mm read as diametral),
width b.  Options:

* ``short_bearing`` (default): Ocvirk's short journal bearing, half-Sommerfeld, with the squeeze
  of the centre's motion: P(theta) = -eta b^3 g(theta)/h^3 with g = u_m h'/r + dh/dt, kept where
  g < 0, u_m = r (omega_land + omega_cage)/2 (both surfaces turn), integrated by a 32-point Gauss
  rule over the positive arc (:func:`guide_land_short_bearing`; the arc's ends are computed, so the
  rule integrates a smooth function).  At the land's b/(2 r) = 0.025 the short-bearing theory is
  within (b/2r)^2 of the finite bearing (tests/test_film_coefficients.py measured the (L/D)^2
  convergence; against the project's FEM at the land itself the load differs by 4e-4, 8e-4 and 3e-3
  at eps = 0.3, 0.5, 0.8, tests/test_laws_cage.py), so the
  FEM map the issue names as a third option is not needed: the cheapest option meets the tolerance.
  Friction torque on the cage: the Couette shear 2 pi eta r^3 b (omega_land - omega_cage) /
  (c sqrt(1 - eps^2)) (the integral of eta r dOmega/h over the full circle).
* ``paper``: eq. 44 as the paper writes it, the roller/crossbeam laws of eq. 34 with the equivalent
  radius r_ic = r_d r_y / (r_y - r_d) of the two conformal circles and h = delta' (eq. 43).

Boundary state below dh0' (eq. 45) as for the pocket.  The reaction on the guiding ring (eq. 46
neglects it) is the negative of the force on the cage; the dynamics applies it or not (option).

All kernels are ``@njit`` leaves (plain floats); forces are magnitudes along the gap's normal
(positive: pushing the surfaces apart).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from .jit import INLINE, JIT

#: Martin's (1916) rigid isoviscous cylinder with the Reynolds exit condition: W h0/(eta u_m R)
#: (lubrication.closed_form.martin_rigid_cylinder computes it: 4.894968...)
MARTIN_COEFFICIENT = 4.894968493913375

POCKET_SWITCHES = {"continuous": 0, "paper": 1}
LAND_FILMS = {"short_bearing": 0, "paper": 1}

# 32-point Gauss-Legendre rule on [-1, 1] (numpy.polynomial.legendre.leggauss)
_GL_X, _GL_W = np.polynomial.legendre.leggauss(32)


@njit(**INLINE)
def cylinder_plane_film(h, mean_speed, approach_speed, radius, length, eta):
    """Film load [N] of a rigid cylinder over a plane: Martin's rolling load plus the squeeze film
    while approaching (module docstring); ``mean_speed`` u_m = (u_1 + u_2)/2 [m/s], ``approach_speed``
    v = -dh/dt [m/s]."""
    q = MARTIN_COEFFICIENT * eta * abs(mean_speed) * radius * length / h
    if approach_speed > 0.0:
        q += 3.0 * math.sqrt(2.0) * math.pi * eta * length * radius ** 1.5 / h ** 1.5 * approach_speed
    return q


@njit(**INLINE)
def cylinder_plane_traction(h, sliding_speed, radius, length, eta):
    """Film traction [N] on a cylinder sliding at ``sliding_speed`` over a plane (eq. 34 as printed,
    eps = 1: (3 pi/sqrt 2) eta u l sqrt(R/h)); odd in the sliding speed."""
    return 3.0 * math.pi / math.sqrt(2.0) * eta * sliding_speed * length * math.sqrt(radius / h)


@njit(**INLINE)
def pocket_force(gap, gap_rate, sliding_speed, radius, length, eta, critical_film, k_h, c_h, mu_bd, switch):
    """``(q, f)``: normal force [N] (>= 0, pushing roller and crossbeam apart) and traction [N] (odd in
    ``sliding_speed``, the roller surface's speed past the beam) of one slice in its pocket
    (module docstring); ``gap`` delta [m], ``gap_rate`` d delta/dt [m/s]; ``switch`` 0 continuous,
    1 the paper's."""
    h = gap if gap > critical_film else critical_film
    approach = -gap_rate if gap > critical_film else 0.0
    q_film = cylinder_plane_film(h, 0.5 * sliding_speed, approach, radius, length, eta)
    f_film = cylinder_plane_traction(h, sliding_speed, radius, length, eta)
    if gap >= critical_film:
        return q_film, f_film
    d = critical_film - gap
    if switch == 1:
        q = k_h * d - c_h * gap_rate + q_film
        if q < 0.0:
            q = 0.0
        return q, mu_bd * q * _sign(sliding_speed) + f_film
    ramp = d / critical_film
    if ramp > 1.0:
        ramp = 1.0
    qs = k_h * d - c_h * ramp * gap_rate
    if qs < 0.0:
        qs = 0.0
    return qs + q_film, mu_bd * qs * _sign(sliding_speed) + f_film


@njit(**INLINE)
def _sign(x):
    return 1.0 if x > 0.0 else (-1.0 if x < 0.0 else 0.0)


@njit(**INLINE)
def side_beam_squeeze(gap, gap_rate, end_diameter, beam_thickness, eta):
    """Squeeze-film force [N] between a roller end and the side beam (parallel strips, module
    docstring): eta d h_s^3 v/h_a^3 while approaching (v = -d h_a/dt > 0), 0 separating."""
    if gap_rate >= 0.0:
        return 0.0
    return eta * end_diameter * beam_thickness ** 3 * (-gap_rate) / gap ** 3


@njit(**JIT)
def guide_land_short_bearing(e_x, e_y, v_x, v_y, radius, clearance, width, eta, surface_speed):
    """``(F_x, F_y)`` [N]: the half-Sommerfeld short-bearing film force on the journal (the land) when
    the bearing (the cage) is displaced so that the film is h = c - e_x cos(theta) - e_y sin(theta)
    (journal centre at (e_x, e_y) relative to the bearing's), the journal centre moving at (v_x, v_y)
    relative to it, and the surfaces' speeds summing to ``surface_speed`` = r (omega_land +
    omega_cage) [m/s]: the frame and the integral of
    :func:`lubrication.closed_form.short_journal_forces`, by a 32-point Gauss rule on the arc where
    the pressure is positive.  The force on the cage is the negative."""
    um = 0.5 * surface_speed
    A = um * e_x / radius - v_y
    B = -um * e_y / radius - v_x
    if A == 0.0 and B == 0.0:
        return 0.0, 0.0
    beta = math.atan2(B, A)
    t0 = math.pi - beta
    half = 0.5 * math.pi
    fx = 0.0
    fy = 0.0
    k = eta * width ** 3
    for i in range(_GL_X.size):
        t = t0 + half * (_GL_X[i] + 1.0)
        c = math.cos(t)
        s = math.sin(t)
        h = clearance - e_x * c - e_y * s
        P = -k * (A * s + B * c) / (h * h * h)
        fx -= _GL_W[i] * P * c
        fy -= _GL_W[i] * P * s
    return fx * half * radius, fy * half * radius


@njit(**INLINE)
def guide_land_torque(eccentricity_ratio, radius, clearance, width, eta, omega_land, omega_cage):
    """Couette friction torque [N m] of the land's film on the cage (positive: dragging it along the
    land's rotation): 2 pi eta r^3 b (omega_land - omega_cage)/(c sqrt(1 - eps^2))."""
    return (2.0 * math.pi * eta * radius ** 3 * width * (omega_land - omega_cage)
            / (clearance * math.sqrt(1.0 - eccentricity_ratio * eccentricity_ratio)))


def equivalent_radius(land_radius: float, cage_radius: float) -> float:
    """r_ic = r_d r_y/(r_y - r_d): the radius of the cylinder over a plane that has the gap of two
    conformal circles near their closest point (the paper's eq. 44 option)."""
    if not 0.0 < land_radius < cage_radius:
        from ..errors import InputError

        raise InputError(f"guide land radius = {land_radius!r} must be > 0 and < the cage's centering radius "
                         f"{cage_radius!r} [m]")
    return land_radius * cage_radius / (cage_radius - land_radius)
