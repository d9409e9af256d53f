r"""One rolling-element/raceway contact of a bearing: curvature, rolling speed, load.

Turns a bearing description into the data of an EHL contact (reduced radii,
entrainment speed, load of the most loaded element).  Rigid rings, no slip,
no centrifugal or gyroscopic loads: the textbook quasi-static picture.

Symbols: D rolling-element diameter (ball, or mean roller diameter), d_m pitch
diameter, alpha contact angle, gamma = D cos(alpha)/d_m, Z number of
elements, f = r/D groove conformity of a ball race (r the groove radius),
B = f_i + f_o - 1, omega_i, omega_o ring speeds [rad/s], F_r, F_a bearing
loads [N].  References: T. A. Harris and M. N. Kotzalas, *Essential Concepts
of Bearing Technology* (5th ed., 2007), ch. 2 (geometry), 7 (load
distribution), 8 (kinematics); B. J. Hamrock and D. Dowson, *Ball Bearing
Lubrication* (1981), ch. 3.

Curvature (x the rolling direction)::

    inner race: R_x = (D/2)(1 - gamma)        outer race: R_x = (D/2)(1 + gamma)
    ball races: R_y = f D/(2 f - 1) = r D/(2 r - D)     roller races: line contact (R_y -> inf)

Kinematics (pure rolling)::

    cage:       omega_c = [omega_i (1 - gamma) + omega_o (1 + gamma)]/2
    entrainment speed at either race, in the frame turning with the cage
    (where the contact stands still, both surfaces move at this speed):
                u_m = (d_m/4)(1 - gamma^2)|omega_i - omega_o|

Most loaded element (Stribeck; Harris & Kotzalas ch. 7)::

    Q_max = c F_r/(Z cos alpha) + F_a/(Z sin alpha)

c = 4.37 (point contacts) or 4.08 (line contacts) for zero clearance, 5 the
classical allowance for clearance.  The axial term is the load every element
carries under F_a alone; adding it to the radial term is an upper estimate.
:func:`ball_load_distribution` solves the combined case instead.

Contact angle of a ball bearing under axial load (Harris & Kotzalas sec. 7.3)::

    free angle:  cos beta0 = 1 - P_d/(2 B D)           (P_d diametral clearance)
    F_a/(Z K_n (B D)^1.5) = sin beta (cos beta0/cos beta - 1)^1.5
    K_n = (K_i^(-2/3) + K_o^(-2/3))^(-3/2),  Q = K delta^1.5 for each race (Hertz)

Quasi-static load distribution of a ball bearing (Jones' rigid-ring model,
Harris & Kotzalas sec. 7.4): ring displacements (delta_a, delta_r); element j
at azimuth psi_j = 2 pi j/Z (psi = 0 under the radial load)::

    s_a = B D sin beta0 + delta_a,  s_r = B D cos beta0 + delta_r cos psi_j
    delta_j = sqrt(s_a^2 + s_r^2) - B D,  tan beta_j = s_a/s_r,  Q_j = K_n max(delta_j, 0)^1.5
    F_r = sum Q_j cos beta_j cos psi_j,  F_a = sum Q_j sin beta_j

K_n is evaluated once, at the free contact angle (its change with the angle
through gamma is below 0.1 % here).

>>> round(entrainment_speed(9.525e-3, 46.005e-3, 0.0, 1000.0), 4)  # 6206, 1000 rad/s
11.0082
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import ConvergenceError, InputError
from . import contact as hertz

STRIBECK = {"point": 4.37, "line": 4.08}


def pitch_ratio(D: float, d_m: float, alpha: float) -> float:
    """gamma = D cos(alpha)/d_m."""
    gamma = D * math.cos(alpha) / d_m
    if not 0.0 <= gamma < 1.0:
        raise InputError(f"bearing: element diameter {D:g} m and pitch diameter {d_m:g} m give "
                         f"gamma = D cos(alpha)/d_m = {gamma:.4g}; it must be < 1")
    return gamma


def race_radius_x(D: float, d_m: float, alpha: float, race: str) -> float:
    """Reduced radius in the rolling direction [m]: (D/2)(1 -+ gamma) for the inner/outer race."""
    gamma = pitch_ratio(D, d_m, alpha)
    return 0.5 * D * (1.0 - gamma if race == "inner" else 1.0 + gamma)


def conformity(D: float, groove_radius: float, key: str = "groove radius") -> float:
    """f = r/D; a ball fits its groove only if f > 1/2."""
    f = groove_radius / D
    if not f > 0.5:
        raise InputError(f"bearing.{key} = {groove_radius:g} m must be > D/2 = {0.5 * D:g} m (conformity r/D > 0.5)")
    return f


def groove_radius_y(D: float, r: float) -> float:
    """Reduced radius across the rolling direction of a ball in a groove of radius ``r``:
    r D/(2 r - D) = f D/(2 f - 1) [m]."""
    return r * D / (2.0 * r - D)


def race_radii(D: float, d_m: float, groove_radius: float, race: str, alpha: float = 0.0) -> tuple[float, float]:
    """(R_x, R_y) [m] of a ball on the ``race`` ("inner"/"outer") groove of radius ``groove_radius`` at
    contact angle ``alpha``: R_x = (D/2)(1 -+ gamma), R_y = r D/(2 r - D)."""
    if race not in ("inner", "outer"):
        raise InputError(f"race = {race!r} is not allowed; choose 'inner' or 'outer'")
    if not groove_radius > 0.5 * D:
        raise InputError(f"{race} groove radius = {groove_radius:g} m must be > D/2 = {0.5 * D:g} m")
    return race_radius_x(D, d_m, alpha, race), groove_radius_y(D, groove_radius)


def cage_speed(D, d_m, alpha, omega_inner, omega_outer=0.0) -> float:
    """omega_c = [omega_i (1 - gamma) + omega_o (1 + gamma)]/2 [rad/s]."""
    gamma = pitch_ratio(D, d_m, alpha)
    return 0.5 * (omega_inner * (1.0 - gamma) + omega_outer * (1.0 + gamma))


def entrainment_speed(D, d_m, alpha, omega_inner, omega_outer=0.0) -> float:
    """u_m = (d_m/4)(1 - gamma^2)|omega_i - omega_o| [m/s], the same at both races."""
    gamma = pitch_ratio(D, d_m, alpha)
    return 0.25 * d_m * (1.0 - gamma**2) * abs(omega_inner - omega_outer)


def stribeck_max_load(radial_load, axial_load, n_elements, alpha, constant) -> float:
    """Q_max = c F_r/(Z cos alpha) + F_a/(Z sin alpha) [N]."""
    q = constant * radial_load / (n_elements * math.cos(alpha))
    if axial_load > 0.0:
        if not math.sin(alpha) > 0.0:
            raise InputError(f"bearing.axial_load = {axial_load:g} N needs a contact angle > 0 (got {math.degrees(alpha):g} deg)")
        q += axial_load / (n_elements * math.sin(alpha))
    return q


# ---------------------------------------------------------------- ball bearings


def free_contact_angle(D, r_inner, r_outer, clearance=0.0) -> float:
    """beta0 from cos beta0 = 1 - P_d/(2 B D), B D = r_i + r_o - D [rad] (0 for zero or negative
    clearance, a preload)."""
    BD = r_inner + r_outer - D
    c = 1.0 - clearance / (2.0 * BD)
    if not -1.0 < c:
        raise InputError(f"bearing.diametral_clearance = {clearance:g} m is larger than the groove geometry allows "
                         f"(must be < 4 B D = {4 * BD:g} m)")
    return math.acos(min(1.0, c))


def deflection_constant(D, d_m, r_inner, r_outer, alpha, e_star) -> float:
    """K_n [N/m^1.5] of the inner and outer contacts in series, Q = K_n delta^1.5 (Hertz)."""
    inv = 0.0
    for race, r in (("inner", r_inner), ("outer", r_outer)):
        hp = hertz.point_contact(1.0, race_radius_x(D, d_m, alpha, race), groove_radius_y(D, r), e_star)
        inv += hp.approach  # delta at Q = 1 N, i.e. K^(-2/3)
    return inv**-1.5


def thrust_contact_angle(axial_load, n_elements, D, r_inner, r_outer, K_n, clearance=0.0) -> float:
    """Contact angle [rad] of every ball under an axial load alone (Harris & Kotzalas sec. 7.3)."""
    from scipy.optimize import brentq

    beta0 = free_contact_angle(D, r_inner, r_outer, clearance)
    if axial_load <= 0.0:
        return beta0
    BD = r_inner + r_outer - D
    target = axial_load / (n_elements * K_n * BD**1.5)

    def residual(beta):
        return math.sin(beta) * max(math.cos(beta0) / math.cos(beta) - 1.0, 0.0) ** 1.5 - target

    hi = 0.5 * math.pi - 1e-9
    if residual(hi) <= 0.0:
        raise InputError(f"bearing.axial_load = {axial_load:g} N is beyond what the grooves carry (contact angle -> 90 deg)")
    return brentq(residual, beta0, hi, xtol=1e-15, rtol=1e-14)


def ball_load_distribution(radial_load, axial_load, n_elements, D, r_inner, r_outer, K_n, clearance=0.0):
    """Element loads Q_j [N] and contact angles beta_j [rad] at psi_j = 2 pi j/Z,
    and the ring displacements (delta_a, delta_r) [m], by Jones' rigid-ring model."""
    from scipy.optimize import brentq, root

    Z = int(n_elements)
    beta0 = free_contact_angle(D, r_inner, r_outer, clearance)
    BD = r_inner + r_outer - D
    psi = 2.0 * np.pi * np.arange(Z) / Z

    def state(delta_a, delta_r):
        s_a = BD * math.sin(beta0) + delta_a
        s_r = BD * math.cos(beta0) + delta_r * np.cos(psi)
        delta = np.hypot(s_a, s_r) - BD
        return K_n * np.maximum(delta, 0.0) ** 1.5, np.arctan2(s_a, s_r)

    if radial_load <= 0.0:  # every ball alike
        beta = thrust_contact_angle(axial_load, Z, D, r_inner, r_outer, K_n, clearance)
        # s_r = B D cos(beta0) (no radial shift) and tan(beta) = s_a/s_r
        delta_a = BD * math.cos(beta0) * math.tan(beta) - BD * math.sin(beta0)
        Q, b = state(delta_a, 0.0)
        return Q, b, delta_a, 0.0
    scale = (radial_load / (Z * K_n)) ** (2.0 / 3.0)
    if axial_load <= 0.0:  # the ring centres itself axially: s_a = 0
        delta_a = -BD * math.sin(beta0)

        def radial(dr):
            Q, b = state(delta_a, dr)
            return np.sum(Q * np.cos(b) * np.cos(psi)) - radial_load

        hi = scale
        while radial(hi) < 0.0:
            hi *= 2.0
        delta_r = brentq(radial, 0.0, hi, xtol=1e-18, rtol=1e-14)
        Q, b = state(delta_a, delta_r)
        return Q, b, delta_a, delta_r
    beta_t = thrust_contact_angle(axial_load, Z, D, r_inner, r_outer, K_n, clearance)
    x0 = np.array([BD * math.cos(beta0) * math.tan(beta_t) - BD * math.sin(beta0), 2.0 * scale]) / scale

    def residual(x):
        Q, b = state(x[0] * scale, x[1] * scale)
        return [np.sum(Q * np.cos(b) * np.cos(psi)) / radial_load - 1.0, np.sum(Q * np.sin(b)) / axial_load - 1.0]

    sol = root(residual, x0, method="hybr", tol=1e-14)
    if not sol.success or max(abs(r) for r in residual(sol.x)) > 1e-9:
        raise ConvergenceError(f"ball load distribution (F_r = {radial_load:g} N, F_a = {axial_load:g} N) did not "
                               f"converge: {sol.message}")
    Q, b = state(sol.x[0] * scale, sol.x[1] * scale)
    return Q, b, sol.x[0] * scale, sol.x[1] * scale


# ---------------------------------------------------------------- the contact


@dataclass(frozen=True)
class RaceContact:
    """The contact of the most loaded element with one race (SI).

    ``radius_y`` is None for a roller (line contact of ``length``); ``load``
    is the element load Q [N]; ``mean_speed`` u_m [m/s]; angles in rad."""

    race: str
    radius_x: float
    radius_y: float | None
    mean_speed: float
    load: float
    contact_angle: float
    gamma: float
    cage_speed: float
    stribeck_constant: float
    load_distribution: str
    length: float | None = None
    free_contact_angle: float = 0.0
    stribeck_load: float | None = None

    @property
    def load_per_length(self) -> float:
        return self.load / self.length


def ball_race_contact(*, race, ball_diameter, pitch_diameter, inner_groove_radius, outer_groove_radius,
                      n_balls, e_star, radial_load=0.0, axial_load=0.0, inner_speed=0.0, outer_speed=0.0,
                      contact_angle=None, clearance=0.0, stribeck_constant=STRIBECK["point"],
                      load_distribution="stribeck") -> RaceContact:
    """The most loaded ball's contact with the ``race`` ("inner" or "outer").

    ``contact_angle`` None: from the groove geometry and the axial load
    (:func:`thrust_contact_angle`).  ``load_distribution``: "stribeck" (Q_max
    estimate with that angle) or "quasi_static" (:func:`ball_load_distribution`;
    the contact angle is then the most loaded ball's own).
    """
    D, d_m = ball_diameter, pitch_diameter
    conformity(D, inner_groove_radius, "inner_groove_radius")
    conformity(D, outer_groove_radius, "outer_groove_radius")
    r_i, r_o = inner_groove_radius, outer_groove_radius
    if radial_load <= 0.0 and axial_load <= 0.0:
        raise InputError("bearing.radial_load and bearing.axial_load are both 0: no ball is loaded")
    beta0 = free_contact_angle(D, r_i, r_o, clearance)
    K_n = deflection_constant(D, d_m, r_i, r_o, beta0, e_star)
    if contact_angle is None:
        contact_angle = thrust_contact_angle(axial_load, n_balls, D, r_i, r_o, K_n, clearance)
    stribeck = stribeck_max_load(radial_load, axial_load, n_balls, contact_angle, stribeck_constant)
    load = stribeck
    if load_distribution == "quasi_static":
        Q, beta, _, _ = ball_load_distribution(radial_load, axial_load, n_balls, D, r_i, r_o, K_n, clearance)
        j = int(np.argmax(Q))
        load, contact_angle = float(Q[j]), float(beta[j])
    r = r_i if race == "inner" else r_o
    return RaceContact(
        race=race, radius_x=race_radius_x(D, d_m, contact_angle, race), radius_y=groove_radius_y(D, r),
        mean_speed=entrainment_speed(D, d_m, contact_angle, inner_speed, outer_speed), load=load,
        contact_angle=contact_angle, gamma=pitch_ratio(D, d_m, contact_angle),
        cage_speed=cage_speed(D, d_m, contact_angle, inner_speed, outer_speed), stribeck_constant=stribeck_constant,
        load_distribution=load_distribution, free_contact_angle=beta0, stribeck_load=stribeck,
    )


def roller_race_contact(*, race, roller_diameter, pitch_diameter, effective_length, n_rollers, contact_angle,
                        radial_load=0.0, axial_load=0.0, inner_speed=0.0, outer_speed=0.0,
                        stribeck_constant=STRIBECK["line"]) -> RaceContact:
    """The most loaded roller's line contact with the ``race`` (Stribeck estimate)."""
    D, d_m = roller_diameter, pitch_diameter
    if radial_load <= 0.0 and axial_load <= 0.0:
        raise InputError("bearing.radial_load and bearing.axial_load are both 0: no roller is loaded")
    load = stribeck_max_load(radial_load, axial_load, n_rollers, contact_angle, stribeck_constant)
    return RaceContact(
        race=race, radius_x=race_radius_x(D, d_m, contact_angle, race), radius_y=None,
        mean_speed=entrainment_speed(D, d_m, contact_angle, inner_speed, outer_speed), load=load,
        contact_angle=contact_angle, gamma=pitch_ratio(D, d_m, contact_angle),
        cage_speed=cage_speed(D, d_m, contact_angle, inner_speed, outer_speed), stribeck_constant=stribeck_constant,
        load_distribution="stribeck", length=effective_length, free_contact_angle=contact_angle, stribeck_load=load,
    )
