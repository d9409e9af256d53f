r"""Contact kernels of the ball bearing: Hertz force with contact damping,
traction, and the ball-ball collision through the oil film.

Set-up functions (plain Python, run once) compute constants; the ``@njit``
kernels are called by the bearing right-hand side (:mod:`lubedyn.dynamics.cageless`).
Symbols: E* reduced modulus ``1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2``; R_a >= R_b
the relative principal radii of the two surfaces (``1/R = 1/R_1 + 1/R_2`` per
direction, concave radii negative); delta the elastic approach [m].

Hertz point contact (``Q = K delta^1.5``)
-----------------------------------------
The set-up laws (reduced modulus, relative radii, the exact and Hamrock-Brewe
ellipse, K_hertz = Q/delta^1.5, springs in series, the Hunt-Crossley alpha)
are written once in :mod:`lubedyn.lubrication.laws.contact` and the race radii in
:mod:`lubedyn.lubrication.laws.bearing`; this module imports nothing else from
:mod:`lubrication`.

Contact damping (Hunt & Crossley 1975)
--------------------------------------
``Q = K delta^1.5 (1 + alpha d(delta)/dt)``, clipped at 0 (no adhesion).  The
damping vanishes with the force at first touch (no jump) and gives a
coefficient of restitution e ~ 1 - (2/3) alpha v_impact; the equivalent
viscous coefficient at a loaded point is c = alpha Q (so alpha ~ 0.1-0.3 s/m
gives a damping ratio of about 0.1 for the loaded ball-race contacts of a
6206).  :func:`hunt_crossley_alpha` converts a restitution coefficient.

Traction (closed form)
----------------------
``mu = mu_lim tanh(|v_s| / max(s0 u_e, v_reg))``: a traction curve over the
slide-to-roll ratio SRR = |v_s|/u_e (initial slope mu_lim/s0, limiting value
mu_lim, as the Newtonian-then-limiting-shear EHL traction curves), regularised
at vanishing entrainment by the sliding speed v_reg (then a smoothed Coulomb
law).  The EHL-map traction is a slot (option ``traction = "map"``) that
:mod:`lubedyn.dynamics.cageless` reserves.

Ball-ball collision (paper B, sec. 2.2, eqs. 8-23, rebuilt)
-----------------------------------------------------------
The paper puts the oil-film stiffness K_L and the Hertz stiffness K_C in
series with the film damping (eq. 8: 1/K_v = 1/K_L + 1/K_C, C_v = C_f), then
splits the collision into an elastic compression phase (eq. 9: Hertz), an
elastic-plastic phase beyond the yield stress sigma (eqs. 10-11: a term
linear in delta and a constant), and an elastic-plastic recovery (eq. 12:
Hertz in (delta - delta_sigma)^{3/2}, i.e. with a residual indentation).  The
extracted equations are garbled (eq. 9 writes a force equal to a stiffness,
eq. 11 mixes delta^1 and delta^1/2 terms of unstated origin, eq. 13
differentiates the film stiffness from the *Hertz* law) and the series
combination of a *viscous* film with a spring is not a spring, so the
physical equivalents used here are:

* Film and solid in series, quasi-steady (the film is a rigid-surface
  isoviscous squeeze film between two spheres, R_eff = R/2, its load carried
  by the elastic(-plastic) flattening of the balls): with g the rigid gap
  (centre distance - D), v = -dg/dt the approach speed, delta_e >= 0 the
  solid approach and h = g + delta_e >= 0 the film thickness::

      F = F_solid(delta_e) = F_film(h, v),  F_film = C0 v [1/(h + h_r) - 1/(h_cut + h_r)]_+,
      C0 = 6 pi eta R_eff^2

  solved for delta_e by a bracketed Newton iteration (F_solid increases and
  F_film decreases with delta_e, so the root is unique).  h_r, the film
  rupture thickness (composite roughness), bounds the film damping C0/h_r;
  h_cut is the starved outer edge of the film.  During separation (v <= 0)
  the film cavitates and carries no tension: F = F_solid(-g) (Hertz
  unloading through the ruptured film) or 0.  When the film cannot carry
  the load at h >= 0 (F_film(0, v) <= F_solid(-g)), the film is ruptured:
  solid contact.  The map option replaces F_film by the tabulated Reynolds
  squeeze force of :mod:`lubedyn.film_points` (kind ``ball_ball``: axes
  central gap, squeeze number or approach speed, entrainment speed; see
  :func:`_film_map`).
* Locked film (map option, polar axes).  The tabulated film is the rigid
  piezoviscous (Barus) film: its pressure number rho = alpha p_iso,max (on the
  approach side) reaches Barus' pole rho = 1 at a finite thickness, where the
  pressure is unbounded and the rigid film has no solution: there the
  surfaces' elastic flattening must carry the load (the EHL regime).  The map
  stops at rho_top = 0.9; the film thickness h_L(v, u_e) at which rho =
  rho_top (:func:`locked_gap`; pure squeeze h_L = sqrt(3 alpha eta0 R_eff
  v/rho_top)) is the thinnest film the rigid model describes.  When the
  solids at the approach h_L - g already carry more than the film can at
  h_L, the film is *locked*: it keeps the thickness h_L and the solids carry
  the load, F = F_solid(h_L - g) (Grubin's reasoning for EHL films: the film
  is set where the rigid-piezoviscous inlet pressure reaches 1/alpha).  The
  force is continuous across the lock; 0.9 instead of 1 makes h_L about 5 %
  thicker for pure squeeze.  h_L uses the map's rho for approach and
  separation alike (so no thicker film lies beyond the map) and the
  entrainment speed regularised over the friction law's slip speed,
  sqrt(u_e^2 + v_reg^2), so that it is smooth in v and u_e: with
  h_L ~ |u_e|^(2/3) or a cut at the map's first squeeze angle, the force
  jumped during rebounds and DOPRI5 rejected half its steps (measured: 39,000
  accepted and 40,000 rejected steps over the first 4 ms of the 10,000 rpm
  drop, against 3,176 and 1,154 with the smooth h_L and 3,402 and 557 with
  the closed-form film).  Above the map's last gap node the polar film is
  self-similar (F = h Phi(rho, theta)) and is scaled, not clamped.  Together
  they leave no state of a collision outside the map's axes.
* Entrapped film's damping (``p.bent`` = beta, ``films.entrapped_damping``).
  The locked solids alone carry the load without loss, but the transient EHL
  impact (:mod:`lubedyn.lubrication.ehl.impact`, paper B's balls and oil)
  loses 68-77 % of its energy while the balls are loaded, through the
  entrapped film.  The locked state therefore adds the damping of Reynolds'
  rigid sphere squeeze film at the lock thickness, beta C0 v/h_L
  (C0 = 6 pi eta0 R_eff^2), weighted by w = 1 - F_film(h_L)/F_solid, the
  solids' share beyond the lock (0 at the lock's onset, so the force stays
  continuous; w -> 1 once loaded), and never pulling (F >= 0).  One constant:
  beta = 1.11 makes a head-on impact at 0.2 m/s restitute as the transient
  (e = 0.904); the same beta predicts 0.05, 0.5 and 1 m/s within 0.006 in
  restitution and 2.1 % in dissipated energy (the undamped lock: 0.829 /
  0.973 / 0.993 / 0.998 against 0.661 / 0.904 / 0.957 / 0.975; its 1 - e
  2-12 times too small).  beta near 1 says the loaded phase dissipates
  about as Reynolds' rigid squeeze film at the lock thickness would (a
  reading of the fit, not a derivation).  Calibrated without entrainment and for
  elastic solids; with entrainment h_L grows and the damping falls
  (unvalidated there); the largest force stays 13-16 % below the
  transient's (the lock thins with the approach speed while the transient's
  entrapped film does not; a lock that keeps h_L(v0), ``h_keep``, brings the
  force within 6-27 % above but needs a state per pair: not adopted).
* Friction (eqs. 16-23, the film-rupture friction): the tangential force on
  the sliding surfaces is mu F_n tanh(|v_s|/v_reg) against the sliding
  velocity (:func:`lubedyn.lubrication.laws.collision.ball_ball_friction_coefficient`).
  Law ``exponential_share`` (default): mu = mu_b f_a + mu_f (1 - f_a), f_a =
  exp(-h/h_r) the asperity share of the load: mu_f (a limiting EHL shear
  coefficient) when the film is intact, the boundary coefficient mu_b when
  it has ruptured (h -> 0).  Law ``paper``: eqs. 17-21 rebuilt, the Barus
  Newtonian shear of eq. 17 limited by mu_f, mixed with mu_b by the
  asperities' share Q_a/F_n of eq. 19 (the film ratio h/h_r and the Hertz
  area of the load) as eq. 20
  (:func:`lubedyn.lubrication.laws.collision.film_rupture_friction_coefficient`).
"""
from __future__ import annotations

import math

from numba import njit

from lubedyn.lubrication.laws.collision import (
    BALL_BALL_DTYPE, PHASE_FILM, PHASE_PLASTIC, PHASE_RECOVERY, PHASE_SEPARATED, ball_ball_friction_coefficient,
    squeeze_film_closed_form, thornton_force,
)
from lubedyn.lubrication.laws.jit import INLINE, JIT

from .interp import hermite3_grad, interp3_grad


# film kinds
FILM_NONE, FILM_CLOSED_FORM, FILM_MAP = 0, 1, 2
FILM_KINDS = {"none": FILM_NONE, "closed_form": FILM_CLOSED_FORM, "map": FILM_MAP}

# map options (int64 array ``map_opts``): log flags of the three axes and the values, interp method, mode,
# kind of the second axis (MAP_AXIS_APPROACH: approach speed v [m/s]; MAP_AXIS_SQUEEZE: squeeze number
# Lambda = 3 alpha eta0 R_eff v/h^2 [-]; MAP_AXIS_POLAR: the polar axes of the ball_ball kind of
# lubedyn.film_points, pressure number rho = sqrt(Lambda^2 + E^2) [-] and squeeze angle theta =
# atan2(Lambda, E) [rad] on the second and third axes, E = 3 alpha eta0 |u_e| sqrt(2 R_eff h)/h^2)
MO_LOG0, MO_LOG1, MO_LOG2, MO_LOGV, MO_METHOD, MO_MODE, MO_AXIS1 = range(7)
MO_SIZE = 7
MAP_AXIS_APPROACH, MAP_AXIS_SQUEEZE, MAP_AXIS_POLAR = 0, 1, 2


# ------------------------------------------------------------------ set-up (Python)
def with_map_ends(p, map_ax0, map_ax1, map_opts):
    """A copy of the ball-ball parameter record ``p``
    (:func:`lubedyn.lubrication.laws.collision.ball_ball_parameters`) with the film map's axis ends in
    physical units (fields ``map_h0``, ``map_htop``, ``map_x1lo``, ``map_x1top``: first and last node of
    the gap and of the second axis, the exponentials of log axes).  The map kernels read them there
    instead of taking ``exp`` of the axis ends on every film read (four exponentials a read, about 10 %
    of a polar read); a record without them (NaN) makes the kernels compute them as before, to the same
    bits."""
    import numpy as np

    out = np.array([p], dtype=BALL_BALL_DTYPE).view(np.recarray)[0]
    if map_ax0 is None:
        return out
    for (lo, hi), ax, log in ((("map_h0", "map_htop"), map_ax0, map_opts[MO_LOG0]),
                              (("map_x1lo", "map_x1top"), map_ax1, map_opts[MO_LOG1])):
        out[lo], out[hi] = ((math.exp(ax[0]), math.exp(ax[-1])) if log == 1 else (float(ax[0]), float(ax[-1])))
    return out


@njit(**INLINE)
def _axis_end(v, ax, i, log):
    """Node ``i`` (0 or -1) of a map axis in physical units: ``v`` (a ``map_*`` field of the parameter record)
    when :func:`with_map_ends` set it, else from the axis."""
    if v == v:
        return v
    return math.exp(ax[i]) if log == 1 else ax[i]


# ------------------------------------------------------------------ kernels


@njit(**JIT)
def _film(h, v, ue, p, film_kind, map_ax0, map_ax1, map_ax2, map_vals, map_opts, counter):
    """Film force F_film(h, v) >= 0 and dF/dh for the chosen film kind."""
    if film_kind == FILM_CLOSED_FORM:
        return squeeze_film_closed_form(h, v, p)
    if film_kind == FILM_MAP:
        if map_vals is None:  # no map given (numba prunes this by type: the map reader is not compiled)
            return math.nan, math.nan
        return _film_map(h, v, ue, p, map_ax0, map_ax1, map_ax2, map_vals, map_opts, counter)
    return 0.0, 0.0


@njit(**JIT)
def _film_map_polar(h, v, ue, p, ax0, ax1, ax2, vals, opts, counter):
    """F and dF/dh (fixed v, u_e) from a ball_ball map on (gap, rho, theta); see :func:`_film_map`."""
    if h >= p.hcut:
        return 0.0, 0.0
    h0 = _axis_end(p.map_h0, ax0, 0, opts[MO_LOG0])
    h_top = _axis_end(p.map_htop, ax0, -1, opts[MO_LOG0])
    floored = h < h0
    if floored:
        h = h0 * (1.0 + 1e-12)  # the first gap node acts as the rupture thickness (no clamp count)
    # above the last gap node the film is self-similar: F = h Phi(rho, theta) exactly, so the map is read at
    # its last gap node and scaled by h/h_top (no clamp)
    above = h > h_top
    hq = h_top * (1.0 - 1e-12) if above else h
    lam = p.sqf * v / (h * h)
    e = p.sqf * abs(ue) * math.sqrt(2.0 / (p.r * h)) / h
    rho = math.sqrt(lam * lam + e * e)
    if rho <= 0.0:
        return 0.0, 0.0
    th = math.atan2(lam, e)
    if th < ax2[0]:
        return 0.0, 0.0
    # d/dh at fixed v, u_e: dLambda/dh = -2 Lambda/h, dE/dh = -1.5 E/h
    dlam, de = -2.0 * lam / h, -1.5 * e / h
    drho = (lam * dlam + e * de) / rho
    dth = (e * dlam - lam * de) / (rho * rho)
    if floored:
        drho, dth = 0.0, 0.0
    rho_lo = _axis_end(p.map_x1lo, ax1, 0, opts[MO_LOG1])
    scale, rq = 1.0, rho
    if rho < rho_lo:
        scale, rq = rho / rho_lo, rho_lo * (1.0 + 1e-12)
    # the reader by the values' type, in this function (numba prunes the other branch only on an argument of
    # the function it compiles): hermite data (8, n0, n1, n2) or linear/pchip values (n0, n1, n2); a
    # model with a hermite map then never compiles the linear/pchip reader (2.4 s of the cold compile)
    if vals.ndim == 4:
        f, d0, d1, d2 = hermite3_grad(ax0, ax1, ax2, opts[MO_LOG0], opts[MO_LOG1], opts[MO_LOG2], vals,
                                      opts[MO_LOGV], hq, rq, th, opts[MO_MODE], counter)
    else:
        f, d0, d1, d2 = interp3_grad(ax0, ax1, ax2, opts[MO_LOG0], opts[MO_LOG1], opts[MO_LOG2], vals,
                                     opts[MO_LOGV], opts[MO_METHOD], hq, rq, th, opts[MO_MODE], counter)
    if f != f:
        return f, f
    if f < 0.0:
        return 0.0, 0.0
    if above:  # F = (h/h_top) scale f(h_top, rq, theta): h enters through the factor, rho and theta
        ext = h / h_top
        if scale < 1.0:
            return ext * scale * f, f * scale / h_top + ext * (scale * d2 * dth + f * drho / rho_lo)
        return ext * f, f / h_top + ext * (d1 * drho + d2 * dth)
    if scale < 1.0:
        return scale * f, scale * (d0 + d2 * dth) + f * drho / rho_lo
    return f, d0 + d1 * drho + d2 * dth


@njit(**JIT)
def _film_map(h, v, ue, p, ax0, ax1, ax2, vals, opts, counter):
    """Tabulated squeeze force over (gap, approach speed or squeeze number,
    entrainment speed), read with :mod:`lubedyn.dynamics.interp` (``vals`` of shape
    (n0, n1, n2) for the linear and pchip methods, (8, n0, n1, n2) from
    ``hermite_data`` for the hermite method: the reader is chosen by the
    array's dimension, at compile time; a two-axis table is given a constant
    third axis by the builder).

    The gap is floored at the map's first node (it plays the role of h_r); an
    approach speed below the first node scales the force linearly in v (the
    isoviscous squeeze film is linear in v); other points outside the axes are
    clamped and counted in ``counter[0]`` (or give NaN with mode 1).  No film
    force during separation (v <= 0: cavitated) or beyond h_cut.  d/dh is
    taken at fixed v (through the squeeze number when that is the axis).

    Polar axes (``MAP_AXIS_POLAR``: gap, pressure number rho, squeeze angle
    theta): a separating film (v < 0) with entrainment carries the tabulated
    load down to the axis' first angle (-80 deg, 2.6e-3 of the squeeze force
    of the same rho), none below; below the first rho node the isoviscous
    scaling F ~ rho holds (:mod:`lubedyn.film_points`, "Polar axes")."""
    if opts[MO_AXIS1] == MAP_AXIS_POLAR:
        return _film_map_polar(h, v, ue, p, ax0, ax1, ax2, vals, opts, counter)
    if v <= 0.0 or h >= p.hcut:
        return 0.0, 0.0
    h0 = _axis_end(p.map_h0, ax0, 0, opts[MO_LOG0])
    if h < h0:
        h = h0 * (1.0 + 1e-12)  # the first gap node acts as the rupture thickness (no clamp count)
    scale = 1.0
    if opts[MO_AXIS1] == MAP_AXIS_SQUEEZE:
        x1 = p.sqf * v / (h * h)
        dx1dh = -2.0 * x1 / h
    else:
        x1 = v
        dx1dh = 0.0
        v0 = _axis_end(p.map_x1lo, ax1, 0, opts[MO_LOG1])
        if v < v0:
            scale = v / v0
            x1 = v0 * (1.0 + 1e-12)  # stay inside the axis after the log/exp round trip
    if vals.ndim == 4:  # by the values' type, as in _film_map_polar
        f, d0, d1, _ = hermite3_grad(ax0, ax1, ax2, opts[MO_LOG0], opts[MO_LOG1], opts[MO_LOG2], vals,
                                     opts[MO_LOGV], h, x1, ue, opts[MO_MODE], counter)
    else:
        f, d0, d1, _ = interp3_grad(ax0, ax1, ax2, opts[MO_LOG0], opts[MO_LOG1], opts[MO_LOG2], vals,
                                    opts[MO_LOGV], opts[MO_METHOD], h, x1, ue, opts[MO_MODE], counter)
    if f != f:
        return f, f
    if f < 0.0:
        return 0.0, 0.0
    return scale * f, scale * (d0 + d1 * dx1dh)


@njit(**JIT)
def locked_gap(v, ue, sqf, radius, rho_lock, u_reg):
    """Film thickness h_L [m] at which the pressure number of the polar axes reaches ``rho_lock``:
    rho^2 = (sqf v)^2 / h^4 + 2 (sqf u)^2 / (R h^3), decreasing in h, solved for u = 1/h by Newton
    from above (the function is convex and increasing in 1/h, so the iterates fall monotonically to the
    root).  rho is the map's own coordinate for approach and separation alike, so no film thicker than
    h_L lies beyond the map; the entrainment speed enters as u = sqrt(u_e^2 + u_reg^2), so that h_L is
    smooth in v and u_e (h_L ~ |u_e|^(2/3) would have an infinite slope at u_e = 0)."""
    a = (sqf * v) ** 2
    b = 2.0 * sqf * sqf * (ue * ue + u_reg * u_reg) / radius
    r2 = rho_lock * rho_lock
    if a <= 0.0 and b <= 0.0:
        return 0.0
    u = 1e300
    if b > 0.0:
        u = (r2 / b) ** (1.0 / 3.0)
    if a > 0.0:
        u = min(u, (r2 / a) ** 0.25)
    for _ in range(60):
        f = (a * u + b) * u * u * u - r2
        df = (4.0 * a * u + 3.0 * b) * u * u
        step = f / df
        u -= step
        if abs(step) <= 1e-14 * u:
            break
    return 1.0 / u


@njit(**JIT)
def _lock(v, ue, p, film_kind, map_ax1, map_vals, map_opts):
    """h_L of a ball_ball film map on polar axes (:func:`locked_gap` at the last pressure-number node,
    entrainment regularised over the friction law's slip speed), else 0: below h_L the rigid piezoviscous
    film has left the map towards Barus' pole (rho = 1, infinite pressure), where the solids' elastic
    flattening carries the load (module docstring, "Locked film")."""
    if film_kind != FILM_MAP:
        return 0.0
    if map_vals is None:
        return 0.0
    if map_opts[MO_AXIS1] != MAP_AXIS_POLAR:
        return 0.0
    rho_top = _axis_end(p.map_x1top, map_ax1, -1, map_opts[MO_LOG1])
    return locked_gap(v, ue, p.sqf, p.r, rho_top * (1.0 - 1e-9), p.vreg)


@njit(**JIT)
def _solid(delta, delta_dot, delta_max, p):
    """Solid force with Hunt-Crossley damping (on the Thornton law)."""
    f, k, ph = thornton_force(delta, delta_max, p)
    if f <= 0.0:
        return 0.0, 0.0, ph
    f2 = f * (1.0 + p.alpha * delta_dot)
    if f2 < 0.0:
        return 0.0, 0.0, ph
    return f2, k * (1.0 + p.alpha * delta_dot), ph


@njit(**JIT)
def ball_ball_normal(g, v, ue, delta_max, p, film_kind, map_ax0, map_ax1, map_ax2, map_vals, map_opts, counter,
                     h_keep=0.0):
    """Normal force between two balls through the film (see the module docstring).

    Parameters: ``g`` rigid gap [m] (centre distance - D), ``v = -dg/dt``
    approach speed [m/s], ``ue`` entrainment speed [m/s] (map only),
    ``delta_max`` plastic memory [m], ``p`` from :func:`ball_ball_parameters`,
    ``film_kind`` (``FILM_*``), map arrays (used for ``FILM_MAP`` only, see
    :func:`_film_map`; a NaN force from a map in mode 1 is returned as NaN).

    Returns ``(F, h, delta_e, phase, share)``: normal force [N] (>= 0, pushes
    the balls apart), film thickness h [m] (0 when ruptured; g when
    separated), solid approach delta_e [m], phase (``PHASE_*``) and the share
    of the approach taken by the solids, d(delta_e)/dt = share * v at fixed v
    (from differentiating F_solid(delta_e) = F_film(g + delta_e, v):
    share = -F_film,h/(F_solid' - F_film,h); 1 for a ruptured film, 0 when
    separated), which drives the plastic memory.

    ``h_keep`` [m] (default 0: none): a film thickness the lock keeps at least, the entrapped film of a
    contact whose lock thickness h_L(v) falls with the approach speed during the compression (the
    transient reference, :mod:`lubedyn.lubrication.ehl.impact`, keeps its entrapped central film at
    0.64-0.69 h_L of the impact speed while h_L(v) itself falls to ~17 nm at the turnaround:
    benchmarks/impact_ehl.py); the lock is then at max(h_L(v), h_keep)."""
    d_solid = -g if g < 0.0 else 0.0
    F_lo, _, ph = _solid(d_solid, v, delta_max, p)
    if film_kind == FILM_NONE:
        if F_lo > 0.0:
            return F_lo, 0.0, d_solid, ph, 1.0
        return 0.0, g if g > 0.0 else 0.0, d_solid, PHASE_SEPARATED, 0.0
    x_lo = d_solid
    h_lock = max(_lock(v, ue, p, film_kind, map_ax1, map_vals, map_opts), h_keep)
    if h_lock > g + d_solid:  # the film at the lower bracket would be thinner than its lock
        x_lo = h_lock - g
        F_lo, k_lock, ph_lock = _solid(x_lo, v, delta_max, p)
        f_lock, _ = _film(h_lock, v, ue, p, film_kind, map_ax0, map_ax1, map_ax2, map_vals, map_opts, counter)
        if f_lock != f_lock:
            return f_lock, h_lock, x_lo, PHASE_FILM, 0.0
        if F_lo >= f_lock:  # locked: the solids carry the load through a film of thickness h_L
            phase = ph_lock if ph_lock == PHASE_PLASTIC or ph_lock == PHASE_RECOVERY else PHASE_FILM
            if p.bent > 0.0 and F_lo > 0.0:
                # the entrapped film's damping while loaded, beta C0 v/h_L, weighted by the solids' share
                # beyond the lock (0 at the lock's onset: the force stays continuous); no tension
                w = 1.0 - f_lock / F_lo if f_lock > 0.0 else 1.0
                F_lo = max(F_lo + p.bent * p.c0 * v / h_lock * w, 0.0)
            return F_lo, h_lock, x_lo, phase, 1.0
    h_lo = g + x_lo  # film thickness at the lower bracket (0 if g < 0)
    f_at, dfdh = _film(h_lo, v, ue, p, film_kind, map_ax0, map_ax1, map_ax2, map_vals, map_opts, counter)
    if f_at != f_at:
        return f_at, h_lo, d_solid, PHASE_FILM, 0.0
    if f_at <= F_lo:  # film cannot carry more than the solid contact: ruptured, or separated
        if F_lo > 0.0:
            return F_lo, 0.0, d_solid, ph, 1.0
        return 0.0, h_lo, d_solid, PHASE_SEPARATED, 0.0
    # root of phi(x) = F_solid(x) - F_film(g + x, v) on x in [x_lo, x_hi]
    lo = x_lo
    # upper bracket: solid approach that carries f_at (the film force can only drop as h grows)
    hi = x_lo + 1e-9
    fs_hi = 0.0
    for _ in range(200):
        fs_hi, _, _ = _solid(hi, v, delta_max, p)
        if fs_hi >= f_at:
            break
        hi = x_lo + 2.0 * (hi - x_lo)
    # start where a Hertz solid (F ~ x^1.5) would carry the film's force at the lower bracket: the root
    # when the film changes little over the solids' approach (a pair far apart against that approach),
    # so Newton needs one or two film reads there instead of about five from the bracket's middle
    x = hi * (f_at / fs_hi) ** (2.0 / 3.0) if fs_hi > 0.0 else 0.5 * (lo + hi)
    if not (lo < x < hi):
        x = 0.5 * (lo + hi)
    phase = PHASE_FILM
    F = 0.0
    dff = dfdh
    for _ in range(60):
        fs, ks, ph = _solid(x, v, delta_max, p)
        ff, dff = _film(g + x, v, ue, p, film_kind, map_ax0, map_ax1, map_ax2, map_vals, map_opts, counter)
        if ff != ff:
            return ff, g + x, x, PHASE_FILM, 0.0
        phi = fs - ff
        if phi > 0.0:
            hi = x
        else:
            lo = x
        dphi = ks - dff
        xn = x - phi / dphi if dphi > 0.0 else 0.5 * (lo + hi)
        if not (lo < xn < hi):
            xn = 0.5 * (lo + hi)
        F = ff
        if abs(xn - x) <= 1e-13 + 1e-10 * abs(x) or hi - lo <= 1e-15:
            x = xn
            break
        x = xn
    fs, ks, ph = _solid(x, v, delta_max, p)
    # the film's slope from the last iterate (within the tolerance of x): one film read saved
    share = -dff / (ks - dff) if ks - dff > 0.0 else 1.0
    F = fs
    h = g + x
    if h < 0.0:
        h = 0.0
    if ph == PHASE_PLASTIC or ph == PHASE_RECOVERY:
        phase = ph
    return F, h, x, phase, share


@njit(**INLINE)  # small leaf of the bearing rhs (see lubedyn.dynamics.cageless)
def plastic_memory_rate(delta_e, delta_e_dot, delta_max, F, p):
    """d(delta_max)/dt: follows the solid approach (rate ``delta_e_dot``) while
    it grows beyond the memory, decays with tau_mem once the pair carries no load."""
    if F > 0.0:
        if delta_e >= delta_max and delta_e_dot > 0.0:
            return delta_e_dot
        return 0.0
    return -delta_max / p.tau


def head_on_impact(p, mass, speed, h_start, film_kind=FILM_MAP, film_map=None, *, h_keep=0.0, rtol=1e-9):
    """One head-on impact of two balls through :func:`ball_ball_normal` (no entrainment, no plastic memory),
    from the rigid gap ``h_start`` [m] at the approach speed ``speed`` [m/s] until the gap is back at
    ``h_start``: the quasi-steady law integrated alone, to compare with the transient EHL reference
    (:func:`lubedyn.lubrication.ehl.impact.simulate_impact`) from the same start.

    ``p`` the law's record (:func:`lubedyn.lubrication.laws.collision.ball_ball_parameters`, with
    :func:`with_map_ends` for a map), ``mass`` the pair's effective mass m1 m2/(m1 + m2) [kg], ``film_map`` a
    :class:`lubedyn.dynamics.cageless.layout.MapArrays` (``FILM_MAP`` only).  scipy's LSODA at ``rtol``, at
    most t_Hertz/200 a step.  Returns a dict: ``restitution`` [-] (NaN if the balls never separate),
    ``force_max`` [N], ``energy_dissipated`` [J], ``h_min`` [m], ``seconds`` (wall time of the integration),
    ``clamped`` (map queries clamped to the axes)."""
    import time

    import numpy as np
    from scipy.integrate import solve_ivp

    from lubedyn.lubrication.laws.contact import hertz_impact

    counter = np.zeros(1, dtype=np.int64)
    m = film_map
    args = ((film_kind, m.ax0, m.ax1, m.ax2, m.values, m.opts, counter) if film_kind == FILM_MAP
            else (film_kind, None, None, None, None, None, counter))
    args = (*args, h_keep)
    duration = hertz_impact(p.r, p.estar, mass, speed).duration

    def rhs(t, y):
        return [y[1], ball_ball_normal(y[0], -y[1], 0.0, 0.0, p, *args)[0] / mass]

    def back(t, y):
        return y[0] - h_start

    back.terminal, back.direction = True, 1
    rhs(0.0, [h_start, -speed])  # compile outside the clock
    t0 = time.perf_counter()
    sol = solve_ivp(rhs, (0.0, 50 * h_start / speed + 20 * duration), [h_start, -speed], method="LSODA",
                    rtol=rtol, atol=[1e-13, 1e-9], max_step=duration / 200, events=back)
    seconds = time.perf_counter() - t0
    out = [ball_ball_normal(g, -v, 0.0, 0.0, p, *args) for g, v in sol.y.T]
    e = sol.y[1, -1] / speed if sol.status == 1 else float("nan")
    return dict(restitution=e, force_max=max(o[0] for o in out), h_min=min(o[1] for o in out),
                energy_dissipated=0.5 * mass * speed**2 * (1 - e * e), seconds=seconds, clamped=int(counter[0]))
