r"""Collision laws of two lubricated balls (paper B, sec. 2.2, rebuilt), written once for films and dynamics.

Hertz force with contact damping (Hunt & Crossley 1975): ``Q = K delta^1.5 (1 + alpha d delta/dt)``,
clipped at 0 (no adhesion); K from :func:`lubedyn.lubrication.laws.contact.hertz_constant`.

Collision phases (Thornton 1997, elastic-perfectly plastic spheres, J.
Appl. Mech. 64:383), the physical content of eqs. 9-12: elastic Hertz
F = K delta^1.5 up to the yield approach delta_y = (pi p_y/(2 E*))^2 R_eff
(F_y = K delta_y^1.5); plastic loading F = F_y + pi p_y R_eff (delta -
delta_y) (linear in delta: eq. 11); recovery (unloading and reloading below
delta_max) Hertz with the enlarged radius R_p and residual indentation
delta_p::

    a_m^2 = (2 F_max + F_y)/(2 pi p_y),  R_p = 4 E* a_m^3/(3 F_max),
    delta_p = delta_max - a_m^2/R_p,     F = (4/3) E* sqrt(R_p) (delta - delta_p)^1.5

(eq. 12 with delta_sigma = delta_p).  p_y = 1.6 sigma_y (onset of yield
below a Hertz contact, Johnson sec. 6.2).  The largest approach delta_max
is a state of the bearing (one per ball pair): d(delta_max)/dt =
d(delta_e)/dt while delta_e >= delta_max and loading, and when the pair has
separated the memory decays with tau_mem (the dented spot rolls out of the
contact; each collision meets fresh surface).

Rigid isoviscous squeeze film of two spheres (R_eff = R/2; Reynolds' sphere-plane squeeze,
e.g. Hamrock, Schmid & Jacobson, *Fundamentals of Fluid Film Lubrication*, 2004, ch. 10):
F = C0 v/h with C0 = 6 pi eta R_eff^2 (:func:`squeeze_film_closed_form`).

The parameters of a ball pair travel as one numba structured record (:data:`BALL_BALL_DTYPE`, read by
name: ``p.hcut``; made by :func:`ball_ball_parameters`) so that numba kernels take one argument.  The
kernels are ``@njit``: :mod:`dynamics` calls them compiled, Python callers call the same code (compiled
on first call, or ``.py_func`` for the interpreted one).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..errors import InputError
from .contact import positive as _positive
from .jit import INLINE, JIT


# ball-ball collision phases (returned by ball_ball_normal)
PHASE_SEPARATED, PHASE_FILM, PHASE_ELASTIC, PHASE_PLASTIC, PHASE_RECOVERY = 0, 1, 2, 3, 4
PHASE_NAMES = ("separated", "film", "elastic", "elastic-plastic", "recovery")

# the ball-ball law's parameters: one named field each, the record of BALL_BALL_DTYPE the laws read by name
# (p.hcut); the integer option first (int64), then the floats.  map_*: the film map's axis ends [m, m, -, -]
# (first and last gap node, first and last pressure-number node), filled by
# lubedyn.dynamics.contacts.with_map_ends for the map the kernels read, NaN until then
BALL_BALL_OPTIONS = (("flaw", "friction law (FRICTION_LAWS)"),)
BALL_BALL_FIELDS = (
    ("k", "Hertz constant K = (4/3) E* sqrt(R_eff) [N/m^1.5]"), ("r", "effective radius R_eff = R/2 [m]"),
    ("estar", "reduced modulus E* [Pa]"), ("py", "yield pressure p_y [Pa] (inf: elastic only)"),
    ("dy", "yield approach delta_y [m]"), ("fy", "yield force F_y [N]"),
    ("alpha", "Hunt-Crossley damping alpha [s/m]"), ("c0", "squeeze film constant C0 = 6 pi eta R_eff^2 [N s]"),
    ("hr", "film rupture thickness h_r [m]"), ("hcut", "film cut-off gap h_cut [m]"),
    ("muf", "film friction coefficient mu_f [-]"), ("mub", "boundary friction coefficient mu_b [-]"),
    ("vreg", "slip regularisation speed [m/s]"), ("tau", "plastic memory time tau_mem [s]"),
    ("sqf", "squeeze number factor 3 alpha eta0 R_eff [m s]"), ("eta", "viscosity eta0 [Pa s]"),
    ("pva", "pressure-viscosity coefficient alpha [m^2/N]"), ("slope", "asperity slope sigma_theta [-]"),
    ("bent", "entrapped-film damping factor beta [-]: the locked film damps with beta C0/h_L (0: none)"),
    ("map_h0", "film map's first gap node [m]"), ("map_htop", "film map's last gap node [m]"),
    ("map_x1lo", "film map's first second-axis node"), ("map_x1top", "film map's last second-axis node"),
)
BALL_BALL_DTYPE = np.dtype([(name, np.int64) for name, _ in BALL_BALL_OPTIONS]
                           + [(name, np.float64) for name, _ in BALL_BALL_FIELDS], align=True)

#: beta of the locked film's damping beta C0 v/h_L (``entrapped_damping``; C0 = 6 pi eta0 R_eff^2, h_L the lock
#: thickness of lubedyn.dynamics.contacts.locked_gap): fitted so that one head-on impact of paper B's balls at
#: 0.2 m/s restitutes as the transient EHL reference (lubedyn.lubrication.ehl.impact, 160 nodes: e = 0.9042);
#: with it the law predicts 0.05 / 0.5 / 1.0 m/s within 0.006 in restitution and 2.1 % in energy dissipated
#: (benchmarks/impact_ehl.py --calibrate; tests/test_entrapped_film.py checks it against the transient)
ENTRAPPED_DAMPING = 1.11

# ball-ball friction laws (field flaw; :func:`ball_ball_friction_coefficient`)
FRICTION_LAWS = {"exponential_share": 0, "paper": 1}


# ------------------------------------------------------------------ set-up (Python)


def yield_onset(radius_eff: float, e_star: float, yield_stress: float) -> tuple[float, float, float]:
    """First yield of a circular Hertz contact: ``(p_y, delta_y, Q_y)`` [Pa, m, N].

    Yield starts below the surface when p0 = 1.6 Y (Tresca/von Mises, nu = 0.3; Johnson 1985,
    sec. 6.2).  With a = pi p0 R/(2 E*): delta_y = (pi p_y/(2 E*))^2 R_eff and
    Q_y = K delta_y^1.5 = pi^3 p_y^3 R_eff^2/(6 E*^2), K = (4/3) E* sqrt(R_eff)."""
    p_y = 1.6 * _positive("yield stress [Pa]", yield_stress)
    delta_y = (math.pi * p_y / (2.0 * e_star)) ** 2 * radius_eff
    return p_y, delta_y, 4.0 / 3.0 * e_star * math.sqrt(radius_eff) * delta_y**1.5


def ball_ball_parameters(*, ball_radius, e_star, yield_stress=None, damping_alpha=0.0, viscosity=0.0,
                         rupture_thickness=1e-7, cutoff_gap=None, mu_film=0.03, mu_boundary=0.1,
                         slip_regularisation=0.01, memory_time=1e-4, pressure_viscosity=0.0,
                         friction_law="exponential_share", asperity_slope=0.02, entrapped_damping=0.0) -> np.record:
    """Parameter record (:data:`BALL_BALL_DTYPE`, read by name: ``p.hcut``) of the ball-ball collision law.

    ``yield_stress`` [Pa] None: elastic only (p_y = inf).  ``viscosity`` [Pa s]
    of the squeeze film (closed form); ``rupture_thickness`` h_r [m],
    ``cutoff_gap`` h_cut [m] (default R/10), ``memory_time`` tau_mem [s],
    ``pressure_viscosity`` alpha [m^2/N] (a map over the squeeze number; the paper's friction law);
    ``friction_law`` one of :data:`FRICTION_LAWS` (see :func:`ball_ball_friction_coefficient`),
    ``asperity_slope`` sigma_theta [-] of the paper's law (eq. 19); ``entrapped_damping`` beta [-] of the
    locked film's damping beta C0 v/h_L (:func:`lubedyn.dynamics.contacts.ball_ball_normal`; 0: none).

    Returns the row of a one-row record array (:func:`ball_ball_row` gives the array the bearing's kernels
    take); njit laws and their ``py_func`` take it as it is.
    """
    R = _positive("ball radius [m]", ball_radius)
    Reff = 0.5 * R
    e_star = _positive("E* [Pa]", e_star)
    p = np.zeros(1, dtype=BALL_BALL_DTYPE).view(np.recarray)[0]
    p.k = 4.0 / 3.0 * e_star * math.sqrt(Reff)
    p.r = Reff
    p.estar = e_star
    if yield_stress is None:
        p.py, p.dy, p.fy = np.inf, np.inf, np.inf
    else:
        p.py, p.dy, p.fy = yield_onset(Reff, e_star, yield_stress)
    if damping_alpha < 0.0:
        raise InputError(f"ball-ball damping alpha = {damping_alpha!r} must be >= 0 [s/m]")
    p.alpha = damping_alpha
    if viscosity < 0.0:
        raise InputError(f"viscosity = {viscosity!r} must be >= 0 [Pa s]")
    p.c0 = 6.0 * math.pi * viscosity * Reff**2
    p.hr = _positive("film rupture thickness [m]", rupture_thickness)
    p.hcut = _positive("film cut-off gap [m]", 0.1 * R if cutoff_gap is None else cutoff_gap)
    for key, mu in (("mu_film", mu_film), ("mu_boundary", mu_boundary)):
        if not 0.0 <= mu < 10.0:
            raise InputError(f"{key} = {mu!r} must lie in [0, 10)")
    p.muf, p.mub = mu_film, mu_boundary
    p.vreg = _positive("slip regularisation speed [m/s]", slip_regularisation)
    p.tau = _positive("plastic memory time [s]", memory_time)
    p.sqf = 3.0 * pressure_viscosity * viscosity * Reff
    if friction_law not in FRICTION_LAWS:
        raise InputError(f"friction_law = {friction_law!r} is not allowed; choose one of {', '.join(FRICTION_LAWS)}")
    p.flaw = FRICTION_LAWS[friction_law]
    p.eta, p.pva = viscosity, pressure_viscosity
    p.slope = _positive("asperity slope [-]", asperity_slope)
    if not 0.0 <= entrapped_damping < 100.0:
        raise InputError(f"entrapped_damping = {entrapped_damping!r} must lie in [0, 100) [-]")
    p.bent = entrapped_damping
    p.map_h0 = p.map_htop = p.map_x1lo = p.map_x1top = np.nan
    return p


def ball_ball_row(p) -> np.recarray:
    """A copy of the parameter record ``p`` (:func:`ball_ball_parameters`) as a record array of one row, the
    form the bearing's kernels take (they read its row, ``args.bbp[0]``): numba takes an array from Python
    at the cost of any array, a record scalar costs ten times more."""
    return np.array([p], dtype=BALL_BALL_DTYPE).view(np.recarray)


# ------------------------------------------------------------------ paper B's film and friction laws (Python)


def series_stiffness(k_film: float, k_hertz: float) -> float:
    """Film and Hertz springs in series (paper B eq. 8 rebuilt): K_f K_H/(K_f + K_H) [N/m].

    Either stiffness <= 0 (no film load, or no contact) makes the other one
    act alone: the series law holds only where both carry the same force.
    """
    if k_film <= 0.0:
        return max(k_hertz, 0.0)
    if k_hertz <= 0.0:
        return k_film
    return k_film * k_hertz / (k_film + k_hertz)


def series_film_hertz(k_film: float, c_film: float, delta: float, radius_eff: float, e_star: float) -> tuple:
    """Paper B's equivalent contact (eq. 8): ``(K_v, C_v)`` = (series film/Hertz stiffness, film damping).

    The Hertz stiffness dQ/d delta = 2 E* sqrt(R_eff delta) (Johnson 1985, eqs. 4.22-4.23) is taken
    at the elastic approach ``delta`` [m] that the contact force produces (0 for delta <= 0).
    """
    k_h = 2.0 * e_star * math.sqrt(radius_eff * delta) if delta > 0.0 else 0.0
    return series_stiffness(k_film, k_h), c_film


@njit(**INLINE)  # leaf of the bearing rhs (paper B's friction law) and a Python law
def barus_hertz_friction_coefficient(eta0, alpha, sliding_speed, film, p0):
    """Film friction coefficient of paper B eq. (17) rebuilt [-].

    Newtonian shear eta0 exp(alpha p) U/h over a Hertzian pressure
    p0 sqrt(1 - r^2/a^2) on a circle, divided by the load (2/3) pi a^2 p0::

        mu = 3 eta0 U [e^(alpha p0) (alpha p0 - 1) + 1] / (h alpha^2 p0^3)

    which tends to 1.5 eta0 U/(h p0) as alpha -> 0 (isoviscous: friction
    eta0 U pi a^2/h over load (2/3) pi a^2 p0).  Unbounded in alpha p0 (inf beyond
    alpha p0 = 700): :func:`film_rupture_friction_coefficient` limits it.
    """
    x = alpha * p0
    if x < 1e-4:  # series: e^x (x - 1) + 1 = x^2/2 + x^3/3 + ...
        bracket_over_x2 = 0.5 + x / 3.0
    elif x > 700.0:
        return math.inf
    else:
        bracket_over_x2 = (math.exp(x) * (x - 1.0) + 1.0) / (x * x)
    return 3.0 * eta0 * sliding_speed * bracket_over_x2 / (film * p0)


@njit(**INLINE)  # leaf of the bearing rhs (paper B's friction law) and a Python law
def mixed_friction_coefficient(mu_fluid, mu_boundary, asperity_share):
    """Film-rupture (mixed) friction coefficient, paper B eq. (20) rebuilt [-].

    mu = mu_fluid (1 - s) + mu_boundary s with s = Q_asperity/Q in [0, 1]
    (clipped): fluid friction on the film's share of the load, boundary
    friction mu_b on the asperities'.
    """
    s = min(max(asperity_share, 0.0), 1.0)
    return mu_fluid * (1.0 - s) + mu_boundary * s


@njit(**INLINE)  # leaf of the bearing rhs (paper B's friction law) and a Python law
def asperity_load_function(film_ratio):
    """The film-parameter function of paper B eq. (19) as read here [-]:
    ``f(lambda) = 17 exp(-2.84 lambda) + 1.44e-4 (4 - lambda)_+^7.8``.

    The extracted text prints ``17 e^(2.84 lambda) + 1.44 x 10^4 (lambda 2)^1.1 4 lambda 7.8``: read as
    a decaying exponential (the asperities' share must fall as the film grows) plus a term of the
    Greenwood-Tripp form (4 - lambda)^p (their F_5/2 fit is 4.4086e-5 (4 - lambda)^6.804), which
    vanishes at lambda = 4 (full film); the printed factor "(lambda 2)^1.1" was left out: as
    (lambda - 2)^1.1 it is complex below lambda = 2, as (lambda^2)^1.1 it would make f grow with
    lambda.  f(0) = 24.2, f(1) = 1.75, f(2) = 0.090, f(4) = 6.9e-5."""
    lam = max(film_ratio, 0.0)
    f = 17.0 * math.exp(-2.84 * lam)
    if lam < 4.0:
        f += 1.44e-4 * (4.0 - lam) ** 7.8
    return f


@njit(**INLINE)  # leaf of the bearing rhs (paper B's friction law) and a Python law
def asperity_load_share(load, film_ratio, radius_eff, e_star, slope):
    """Q_a/F_n: the share of a ball pair's load the asperities carry, paper B eq. (19) rebuilt [-].

    ``Q_a = E' A sigma_theta f(lambda)/(4 pi^2)`` (eq. 19) with E' = 2 E*, A = pi a^2 the Hertz
    area of the load F_n (a^3 = 3 F_n R_eff/(4 E*)), sigma_theta the asperity slope and f
    :func:`asperity_load_function`; so Q_a/F_n = E* a^2 sigma_theta f(lambda)/(2 pi F_n), which
    falls as F_n^(-1/3) at a fixed film ratio (the asperities' share of a light load is larger).
    Not clipped (the caller clips to [0, 1])."""
    if load <= 0.0:
        return 1.0
    a2 = (3.0 * load * radius_eff / (4.0 * e_star)) ** (2.0 / 3.0)
    return e_star * a2 * slope * asperity_load_function(film_ratio) / (2.0 * math.pi * load)


@njit(**INLINE)  # leaf of the bearing rhs (paper B's friction law) and a Python law
def film_rupture_friction_coefficient(load, film, sliding_speed, eta0, alpha, radius_eff, e_star, roughness,
                                      slope, mu_limit, mu_boundary):
    """Paper B's friction coefficient of two balls sliding through their film, eqs. (17)-(21) rebuilt [-].

    With p0 = (6 F_n E*^2/(pi^3 R_eff^2))^(1/3) the Hertz pressure of the load (the film's pressure
    scale), lambda = h/sigma (sigma the composite roughness) and s = Q_a/F_n clipped to [0, 1]
    (:func:`asperity_load_share`)::

        mu_fluid = mu_lim tanh(mu_17/mu_lim)            (eq. 17, limited)
        mu       = mu_fluid (1 - s) + mu_b s            (eq. 20)

    and the film-rupture friction force f_i = mu F_n (eq. 21).  Eq. 17 is Newtonian shear
    eta0 e^(alpha p) U/h: at the pressures of a collision (alpha p0 = 20-60) it exceeds any
    lubricant's limiting shear stress by orders of magnitude, so it is limited smoothly by
    mu_lim (``friction_film``): Newtonian below, limiting-shear traction above (the shape of EHL
    traction curves).  Eq. 18's tangential *stiffness* (a spring in the tangential direction) is
    not modelled: neighbouring balls roll in the same sense, so their surfaces slide past each
    other at about twice the surface speed (m/s), never sticking; the tangential damping of eq. 18
    is the viscous shear mu_17 F_n/U of eq. 17.  Eq. 22 (the angular deviation atan(F_t/F_n)) and
    eq. 23 (the resultant) follow from adding the normal and tangential forces as vectors, which
    the bearing's right-hand side does."""
    if load <= 0.0 or sliding_speed <= 0.0:
        return 0.0
    p0 = (6.0 * load * e_star * e_star / (math.pi ** 3 * radius_eff * radius_eff)) ** (1.0 / 3.0)
    h = max(film, 1e-3 * roughness)  # the Newtonian term ~ 1/h: a film of zero thickness shears at the limit
    x = barus_hertz_friction_coefficient(eta0, alpha, sliding_speed, h, p0) / mu_limit if mu_limit > 0.0 else 0.0
    mu_fluid = mu_limit * math.tanh(min(x, 50.0))
    share = asperity_load_share(load, film / roughness, radius_eff, e_star, slope)
    return mixed_friction_coefficient(mu_fluid, mu_boundary, share)


def barus_squeeze_film(h0: float, v: float, eta0: float, alpha: float, radius_eff: float) -> tuple:
    """Closed-form rigid Barus squeeze film of two balls: ``(F [N], K [N/m], C [N s/m])``.

    Infinite parabolic film, incompressible oil, no entrainment, Reynolds
    cavitation at ambient (module docstring).  With F_iso = 6 pi eta0
    R_eff^2 v/h0, Lambda = 3 alpha eta0 R_eff v/h0^2,
    I(L) = 2 sqrt(L) artanh(sqrt(L)) + ln(1 - L) = sum_k L^(k+1)/((k + 1)(2k + 1))
    and I'(L) = artanh(sqrt(L))/sqrt(L)::

        F = F_iso I(L)/L,   C = dF/dv = 6 pi eta0 R_eff^2 I'(L)/h0,
        K = -dF/dh0 = (F_iso/h0) (2 I'(L) - I(L)/L)

    alpha = 0 gives the isoviscous F = F_iso, K = F/h0, C = F/v.
    Separation (v <= 0): (0, 0, 0).  At and beyond the pole (L >= 1) the
    rigid film has no solution: returns (F(1) = 2 ln 2 F_iso, inf, inf); the
    caller must switch to the elastic contact law there.  Plain floats only
    (numba-portable).  Within 0.2 % of the map kind ``ball_ball`` with an
    incompressible oil and h_a = 1000 h0; Dowson-Higginson adds ~1 %.
    """
    if v <= 0.0:
        return 0.0, 0.0, 0.0
    c_iso = 6.0 * math.pi * eta0 * radius_eff * radius_eff / h0  # C of the isoviscous film
    f_iso = c_iso * v
    lam = 3.0 * alpha * eta0 * radius_eff * v / (h0 * h0)
    if lam >= 1.0:
        return 2.0 * math.log(2.0) * f_iso, math.inf, math.inf
    if lam < 1e-4:  # series (also alpha = 0): I/L = 1 + L/6 + L^2/15, I' = 1 + L/3 + L^2/5
        g = 1.0 + lam / 6.0 + lam * lam / 15.0
        dI = 1.0 + lam / 3.0 + lam * lam / 5.0
    else:
        s = math.sqrt(lam)
        g = (2.0 * s * math.atanh(s) + math.log1p(-lam)) / lam
        dI = math.atanh(s) / s
    return f_iso * g, f_iso / h0 * (2.0 * dI - g), c_iso * dI


# ------------------------------------------------------------------ kernels


@njit(**INLINE)  # small leaf of the bearing rhs (see lubedyn.dynamics.cageless)
def hertz_force(delta, delta_dot, K, alpha):
    """Hunt-Crossley Hertz force ``K delta^1.5 (1 + alpha delta_dot)``, >= 0; 0 for delta <= 0."""
    if delta <= 0.0:
        return 0.0
    f = K * delta * math.sqrt(delta) * (1.0 + alpha * delta_dot)
    return f if f > 0.0 else 0.0


@njit(**JIT)
def thornton_force(delta, delta_max, p):
    """Elastic-perfectly plastic sphere contact (Thornton 1997), without damping.

    Returns ``(F, dF/ddelta, phase)`` for the solid approach ``delta`` and the
    largest approach so far ``delta_max`` (parameters ``p`` from
    :func:`ball_ball_parameters`).  phase: 2 elastic, 3 plastic loading, 4
    recovery (below delta_max after yielding)."""
    if delta <= 0.0:
        return 0.0, 0.0, PHASE_SEPARATED
    K, R, es, py, dy, Fy = p.k, p.r, p.estar, p.py, p.dy, p.fy
    if delta <= dy and delta_max <= dy:
        s = math.sqrt(delta)
        return K * delta * s, 1.5 * K * s, PHASE_ELASTIC
    if delta >= delta_max:  # on the loading envelope, beyond yield
        if delta <= dy:
            s = math.sqrt(delta)
            return K * delta * s, 1.5 * K * s, PHASE_ELASTIC
        return Fy + math.pi * py * R * (delta - dy), math.pi * py * R, PHASE_PLASTIC
    Fm = Fy + math.pi * py * R * (delta_max - dy)
    am2 = (2.0 * Fm + Fy) / (2.0 * math.pi * py)
    Rp = 4.0 * es * am2 * math.sqrt(am2) / (3.0 * Fm)
    dp = delta_max - am2 / Rp
    x = delta - dp
    if x <= 0.0:
        return 0.0, 0.0, PHASE_SEPARATED
    Kp = 4.0 / 3.0 * es * math.sqrt(Rp)
    s = math.sqrt(x)
    return Kp * x * s, 1.5 * Kp * s, PHASE_RECOVERY


@njit(**JIT)
def residual_indentation(delta_max, p):
    """delta_p [m] left after unloading from ``delta_max`` (0 if never yielded)."""
    dy = p.dy
    if delta_max <= dy:
        return 0.0
    R, es, py, Fy = p.r, p.estar, p.py, p.fy
    Fm = Fy + math.pi * py * R * (delta_max - dy)
    am2 = (2.0 * Fm + Fy) / (2.0 * math.pi * py)
    Rp = 4.0 * es * am2 * math.sqrt(am2) / (3.0 * Fm)
    return delta_max - am2 / Rp


@njit(**JIT)
def squeeze_film_closed_form(h, v, p):
    """Rigid isoviscous squeeze film between two spheres (R_eff = R/2) and its
    derivative d/dh: ``C0 v [1/(h + h_r) - 1/(h_cut + h_r)]`` for v > 0 and
    h < h_cut, else 0 (cavitated during separation; starved beyond h_cut).

    Reynolds' sphere-plane squeeze film F = 6 pi eta R^2 v/h (h << R) with
    the rupture thickness h_r as an offset that bounds it at contact."""
    if v <= 0.0 or h >= p.hcut:
        return 0.0, 0.0
    hr = p.hr
    inv = 1.0 / (h + hr)
    return p.c0 * v * (inv - 1.0 / (p.hcut + hr)), -p.c0 * v * inv * inv


@njit(**INLINE)  # small leaf of the bearing rhs (see lubedyn.dynamics.cageless)
def ball_ball_friction_coefficient(h, load, sliding_speed, p):
    """Friction coefficient of a ball pair [-] by the law ``p.flaw`` (:data:`FRICTION_LAWS`).

    ``exponential_share``: mu = mu_b f_a + mu_f (1 - f_a), f_a = exp(-h/h_r) (the asperities' share of
    the load falls exponentially with the film over the composite roughness h_r);
    ``paper``: :func:`film_rupture_friction_coefficient` (paper B eqs. 17-21, h_r as the roughness)."""
    if p.flaw == 1:
        return film_rupture_friction_coefficient(load, h, sliding_speed, p.eta, p.pva, p.r, p.estar,
                                                 p.hr, p.slope, p.muf, p.mub)
    fa = math.exp(-h / p.hr)
    return p.mub * fa + p.muf * (1.0 - fa)
