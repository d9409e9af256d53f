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
:func:`lubedyn.lubrication.laws.grease` readings).  Eq. 34's damping c_e = 6 pi eps phi0 l_e varsigma^(3/2)
/ (sqrt(2) n_s h0^(3/2)) is exactly the squeeze film of a rigid cylinder approaching a plane with a
full film (p = 6 eta v R/h^2, integrated: 3 sqrt(2) pi eta v R^(3/2)/h^(3/2) per unit length) with
eps = 1, varsigma = R, l = l_e/n_s; during separation the film cavitates (half-Sommerfeld) and the
squeeze force is 0.  The traction is eq. 34's as printed (eps = 1): 3/2 of the Couette shear
eta u pi sqrt(2R/h) of the whole uncavitated film, measured 9.3 % above the project's FEM shear on
the sliding roller over a Reynolds-cavitated film (tests/test_laws_cage.py).

The "paper" film law (``film_law`` 1, eqs. 34-35 rebuilt).  Eq. 35's f(h0) is garbled in the
extracted text; its readable structure is f = xi_1 phi u^n/h0^n [(2/n)^n + xi_2 lambda^n tau_y
h0^n/(xi_1 phi u^n)], i.e. a power-law load plus a yield-stress load that does not depend on h0.
Rebuilt from physics: Martin's load with the Herschel-Bulkley apparent viscosity eta_a = tau_y/D +
phi D^(n-1) at the film's nominal shear rate D = |u|/h0 (u the roller surface's speed past the beam,
u_m = u/2)::

    f(h0) = (c_M/2) R l [phi (|u|/h0)^n + tau_y],      k_e = df/dh0 = -n (c_M/2) R l phi |u|^n/h0^(n+1)
    q_paper = |k_e| h0 - c_e d(delta)/dt (both signs, as printed), clipped at 0

Eq. 34 writes the load as k_e delta with delta = h0; taken as the magnitude |k_e| h0 (k_e < 0 would
pull the roller onto the beam).  In the Newtonian limit (tau_y = 0, n = 1, phi = eta) q_paper is
Martin's load exactly; the yield stress drops out of k_e (it is constant in h0), which is the
paper's Fig. 15 ("little effect").  Squeeze and traction use ``eta`` (the caller's viscosity
reading; :mod:`lubedyn.lubrication.laws.grease`), as eq. 34 uses phi0 as a viscosity.

Martin's coefficient: 4.8950 eta u_m R/h (Reynolds exit condition; Martin 1916; Hamrock, Schmid &
Jacobson 2004, eq. 17.28), the same as 2.4475 eta (u_1 + u_2) R/h.  The half-Sommerfeld (Guembel)
film gives 4.0 eta u_m R/h (:data:`HALF_SOMMERFELD_COEFFICIENT`), the full Sommerfeld film no load.

Gap (eq. 33): delta = Delta delta - (roller centre's displacement towards the beam), Delta delta =
(l_c - d_w)/2 = 0.27 mm (Table 1) (:func:`pocket_gap`).

Boundary state (delta < dh0, eqs. 36-37): the solids are deformed by delta_h = dh0 - delta and::

    paper:      q = k_h delta_h + c_h d(delta_h)/dt + q_film(dh0),  f = mu_bd q + f_film(dh0)
    continuous: q = k_h delta_h + c_h min(delta_h/dh0, 1) d(delta_h)/dt (>= 0) + q_film(dh0, d delta/dt),
                f = mu_bd (q - q_film) + f_film(dh0)

The paper's switch jumps at delta = dh0 (its damping force c_h d(delta_h)/dt and the boundary
friction mu_bd q_film appear at once, the film's squeeze stops); the continuous switch (default) keeps
the film's squeeze at dh0 with the gap's rate, ramps the damping in with the deformation and applies
mu_bd to the solids' share only, so force and friction are continuous in delta: an adaptive integrator does not have to resolve a jump at every pocket contact.

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
  at eps = 0.3, 0.5, 0.8 with half-Sommerfeld cavitation; with Reynolds cavitation 2.6e-4 to 9.5e-3
  at eps 0.1 to 0.95, attitude within 0.011 deg, tests/test_laws_cage.py), so it stays the default:
  the FEM (tests/test_laws_cage.py) is the independent check.
  Friction torque on the cage: the Couette shear 2 pi eta r^3 b (omega_land - omega_cage) /
  (c sqrt(1 - eps^2)) (the integral of eta r dOmega/h over the full circle).
* ``paper``: eq. 44 as the paper writes it, the roller/crossbeam laws of eq. 34 with the equivalent
  radius r_ic = r_d r_y / (r_y - r_d) of the two conformal circles and h = delta' (eq. 43).

Boundary state below dh0' (eq. 45) as for the pocket (:func:`guide_land_force`: the film is held
at h_min = dh0', the solids add k_h' (dh0' - h_min) + damping, continuous or paper switch, friction
torque mu_bd q r_d).  The reaction on the guiding ring (eq. 46 neglects it, ``keep_reaction`` 0)
is kept by default: the ring gets -F_cage and the torque -T_cage - (e_c x F_cage)_z (e_c the cage
centre relative to the land's), so that the pair conserves linear and angular momentum.

All kernels are ``@njit`` leaves (plain floats); forces are magnitudes along the gap's normal
(positive: pushing the surfaces apart).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from .jit import INLINE, JIT
from ..errors import InputError

#: Martin's (1916) rigid isoviscous cylinder with the Reynolds exit condition: W h0/(eta u_m R)
#: (lubedyn.lubrication.closed_form.martin_rigid_cylinder computes it: 4.894968...)
MARTIN_COEFFICIENT = 4.894968493913375

#: half-Sommerfeld (Guembel) rigid cylinder over a plane, infinite inlet: W h0/(eta u_m R)
#: = 2 int_{-inf}^0 4|xi|/(1 + xi^2)^2 dxi = 4
HALF_SOMMERFELD_COEFFICIENT = 4.0

POCKET_SWITCHES = {"continuous": 0, "paper": 1}
POCKET_FILM_LAWS = {"martin": 0, "paper": 1}
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
def pocket_gap(clearance, displacement):
    """Eq. 33: delta = Delta delta - displacement [m], ``clearance`` Delta delta = (l_c - d_w)/2 (Table 1:
    0.27 mm), ``displacement`` the roller centre's (or the slice point's) move towards the beam [m]."""
    return clearance - displacement


@njit(**INLINE)
def herschel_bulkley_cylinder_load(h, sliding_speed, radius, length, tau_y, phi, n):
    """Eq. 35 rebuilt (module docstring): f(h0) = (c_M/2) R l [phi (|u|/h0)^n + tau_y] [N], Martin's load
    with the Herschel-Bulkley apparent viscosity at the shear rate |u|/h0."""
    return 0.5 * MARTIN_COEFFICIENT * radius * length * (phi * (abs(sliding_speed) / h) ** n + tau_y)


@njit(**INLINE)
def herschel_bulkley_cylinder_stiffness(h, sliding_speed, radius, length, phi, n):
    """Eq. 34's k_e = df/dh0 [N/m] of :func:`herschel_bulkley_cylinder_load` (negative; tau_y drops out)."""
    return -n * 0.5 * MARTIN_COEFFICIENT * radius * length * phi * (abs(sliding_speed) / h) ** n / h


@njit(**INLINE)
def pocket_film_paper(h, gap_rate, sliding_speed, radius, length, eta, tau_y, phi, n):
    """The paper's film load (eq. 34 with eq. 35 rebuilt) [N]: |k_e| h0 - c_e d(delta)/dt, c_e = 3 sqrt(2)
    pi eta l R^1.5/h^1.5 (eq. 34's c_e with eps = 1, varsigma = R, l = l_e/n_s), clipped at 0."""
    q = (-herschel_bulkley_cylinder_stiffness(h, sliding_speed, radius, length, phi, n) * h
         - 3.0 * math.sqrt(2.0) * math.pi * eta * length * radius ** 1.5 / h ** 1.5 * gap_rate)
    return q if q > 0.0 else 0.0


@njit(**INLINE)
def pocket_force(gap, gap_rate, sliding_speed, radius, length, eta, critical_film, k_h, c_h, mu_bd, switch,
                 film_law=0, tau_y=0.0, phi=0.0, n=1.0):
    """``(q, f)``: normal force [N] (>= 0, pushing roller and crossbeam apart) and traction [N] (odd in
    ``sliding_speed``, the roller surface's speed past the beam) of one slice in its pocket
    (module docstring); ``gap`` delta [m], ``gap_rate`` d delta/dt [m/s]; ``switch`` 0 continuous,
    1 the paper's; ``film_law`` 0 Martin + squeeze while approaching, 1 the paper's eq. 34-35
    (Herschel-Bulkley ``tau_y`` [Pa], ``phi`` [Pa s^n], ``n``)."""
    h = gap if gap > critical_film else critical_film
    rate = gap_rate if (gap > critical_film or switch == 0) else 0.0
    if film_law == 1:
        q_film = pocket_film_paper(h, rate, sliding_speed, radius, length, eta, tau_y, phi, n)
    else:
        q_film = cylinder_plane_film(h, 0.5 * sliding_speed, -rate, radius, length, eta)
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


@njit(**INLINE)
def side_beam_force(gap, gap_rate, end_diameter, beam_thickness, eta, critical_film, k_h, c_h):
    """Force [N] (>= 0, pushing roller end and side beam apart) of :func:`side_beam_squeeze` with the
    pocket's boundary state below the critical film (the continuous switch of :func:`pocket_force`): the
    squeeze evaluated at max(h_a, h_crit), plus k_h d - c_h r dh_a/dt where h_a < h_crit (d = h_crit - h_a,
    the damping ramped in by r = min(d/h_crit, 1) as :func:`pocket_force` does; the solids' share, >= 0), so
    the force is continuous in the gap and bounded as it closes."""
    h = gap if gap > critical_film else critical_film
    f = side_beam_squeeze(h, gap_rate, end_diameter, beam_thickness, eta)
    if gap < critical_film:
        d = critical_film - gap
        ramp = d / critical_film if d < critical_film else 1.0
        b = k_h * d - c_h * ramp * gap_rate
        if b > 0.0:
            f += b
    return f


@njit(**JIT)
def guide_land_short_bearing(e_x, e_y, v_x, v_y, radius, clearance, width, eta, surface_speed):
    """``(F_x, F_y)`` [N]: the half-Sommerfeld short-bearing film force on the journal (the land) when
    the bearing (the cage) is displaced so that the film is h = c - e_x cos(theta) - e_y sin(theta)
    (journal centre at (e_x, e_y) relative to the bearing's), the journal centre moving at (v_x, v_y)
    relative to it, and the surfaces' speeds summing to ``surface_speed`` = r (omega_land +
    omega_cage) [m/s]: the frame and the integral of
    :func:`lubedyn.lubrication.closed_form.short_journal_forces`, by a 32-point Gauss rule on the arc where
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


@njit(**INLINE)
def guide_land_paper(e_x, e_y, v_x, v_y, equivalent, clearance, width, eta, surface_speed):
    """``(F_x, F_y)`` [N] on the journal (the land), eq. 44 as printed: the cylinder-over-plane film
    (:func:`cylinder_plane_film`, Martin + squeeze while approaching) with the equivalent radius r_ic
    (:func:`equivalent_radius`), h = c - |e| (eq. 43), u_m = ``surface_speed``/2, along the line of
    centres only (eq. 46: no attitude angle).  Same frame as :func:`guide_land_short_bearing`."""
    e = math.hypot(e_x, e_y)
    if e == 0.0:
        return 0.0, 0.0
    ux = e_x / e
    uy = e_y / e
    q = cylinder_plane_film(clearance - e, 0.5 * surface_speed, v_x * ux + v_y * uy, equivalent, width, eta)
    return -q * ux, -q * uy


@njit(**JIT)
def guide_land_force(c_x, c_y, w_x, w_y, omega_land, omega_cage, radius, clearance, width, eta, equivalent,
                     critical_film, k_h, c_h, mu_bd, film, switch, keep_reaction):
    """The cage on its guide land, eqs. 43-46: ``(Fc_x, Fc_y, Tc, Fr_x, Fr_y, Tr)``, force [N] and torque
    [N m] on the cage and on the guiding ring.  ``(c_x, c_y)`` [m], ``(w_x, w_y)`` [m/s]: the cage centre
    relative to the land's and its velocity; ``film`` one of :data:`LAND_FILMS`; ``switch`` as
    :func:`pocket_force`; ``keep_reaction`` 0 reproduces eq. 46 (the ring gets nothing), 1 (default of
    the model) the momentum-conserving reaction (module docstring)."""
    e = math.hypot(c_x, c_y)
    limit = clearance - critical_film
    ex, ey, vx, vy = -c_x, -c_y, -w_x, -w_y  # the journal (land) relative to the bearing (cage)
    d = 0.0
    if e > limit:  # boundary state: the film is held at h_min = dh0'
        d = e - limit
        ex *= limit / e
        ey *= limit / e
        if switch == 1:  # the paper's: the film at dh0' has no squeeze
            vr = (vx * ex + vy * ey) / limit
            vx -= vr * ex / limit
            vy -= vr * ey / limit
    U = radius * (omega_land + omega_cage)
    if film == 1:
        fx, fy = guide_land_paper(ex, ey, vx, vy, equivalent, clearance, width, eta, U)
    else:
        fx, fy = guide_land_short_bearing(ex, ey, vx, vy, radius, clearance, width, eta, U)
    eps_f = math.hypot(ex, ey) / clearance
    if film == 1:
        h = clearance * (1.0 - eps_f)
        torque = radius * cylinder_plane_traction(h, radius * (omega_land - omega_cage), equivalent, width, eta)
    else:
        torque = guide_land_torque(eps_f, radius, clearance, width, eta, omega_land, omega_cage)
    Fcx = -fx
    Fcy = -fy
    if d > 0.0:
        ux = c_x / e
        uy = c_y / e
        d_rate = w_x * ux + w_y * uy
        if switch == 1:
            qs = k_h * d + c_h * d_rate
        else:
            ramp = d / critical_film
            if ramp > 1.0:
                ramp = 1.0
            qs = k_h * d + c_h * ramp * d_rate
        if qs < 0.0:
            qs = 0.0
        q_film = -(Fcx * ux + Fcy * uy)
        if switch == 1:
            qs_total = qs + (q_film if q_film > 0.0 else 0.0)
            if qs_total < 0.0:
                qs_total = 0.0
            torque += mu_bd * qs_total * radius * _sign(omega_land - omega_cage)
        else:
            torque += mu_bd * qs * radius * _sign(omega_land - omega_cage)
        Fcx -= qs * ux
        Fcy -= qs * uy
    if keep_reaction == 0:
        return Fcx, Fcy, torque, 0.0, 0.0, 0.0
    return Fcx, Fcy, torque, -Fcx, -Fcy, -torque - (c_x * Fcy - c_y * Fcx)


def equivalent_radius(land_radius: float, cage_radius: float) -> float:
    """r_ic = r_d r_y/(r_y - r_d): the radius of the cylinder over a plane that has the gap of two
    conformal circles near their closest point (the paper's eq. 44 option)."""
    if not 0.0 < land_radius < cage_radius:
        raise InputError(f"guide land radius = {land_radius!r} must be > 0 and < the cage's centering radius "
                         f"{cage_radius!r} [m]")
    return land_radius * cage_radius / (cage_radius - land_radius)
