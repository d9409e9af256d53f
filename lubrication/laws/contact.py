r"""Contact laws written once for films and dynamics: Hertz point and line contacts, reduced modulus,
relative radii, contact stiffness, series springs and Hunt-Crossley damping.

Elliptical contact, exact (Johnson, *Contact Mechanics*, 1985, sec. 3.9 and
4.2).  The pressure p0 sqrt(1 - (s/a)^2 - (t/b)^2) on an ellipse with semi-axes
a >= b (a along the direction of the *larger* relative radius R_a), e^2 = 1 -
b^2/a^2, displaces the surfaces (both bodies, reduced modulus E*) by::

    u(s, t) = (p0 b / E*) [K(e) - (K(e) - E(e)) s^2/(e^2 a^2)
                                 - ((a^2/b^2) E(e) - K(e)) t^2/(e^2 a^2)]

Matching u to the gap s^2/(2 R_a) + t^2/(2 R_b) inside the contact gives

    R_a / R_b = ((a/b)^2 E - K) / (K - E)                 (solved for e)
    a^3 = 3 W R_a (K - E) / (pi E* e^2),   p0 = 3 W / (2 pi a b)
    delta = p0 b K(e) / E*                               (approach)

with K, E the complete elliptic integrals of modulus e (``scipy.special.ellipk``
and ``ellipe`` take the parameter m = e^2).  The circular limit e -> 0 gives
a^3 = 3 W R / (4 E*), delta = a^2 / R.

Hamrock & Brewe (1983, J. Tribol. 105:171) approximations (option): with
k = a/b = 1.0339 (R_a/R_b)^0.636, E = 1.0003 + 0.5968 R_b/R_a,
F = 1.5277 + 0.6023 ln(R_a/R_b), 1/R = 1/R_a + 1/R_b and E' = 2 E*::

    a = (6 k^2 E W R / (pi E'))^(1/3),  b = (6 E W R / (pi k E'))^(1/3),
    delta = F (9/(2 E R) (W/(pi k E'))^2)^(1/3)

Line contact (per unit length W' [N/m]): b = sqrt(4 W' R / (pi E*)),
p0 = 2 W' / (pi b) (Johnson eq. 4.45).

Stiffness: Q = K delta^1.5 with K = Q/delta^1.5 at Q = 1 N (:func:`hertz_constant`); the circle
gives K = (4/3) E* sqrt(R).  Two contacts carrying the same load in series (inner and outer race):
K = (K1^-2/3 + K2^-2/3)^-3/2.  Hunt & Crossley (1975) damping Q = K delta^1.5 (1 + alpha d delta/dt)
with alpha = 3 (1 - e)/(2 v_impact) for a coefficient of restitution e (:func:`hunt_crossley_alpha`;
the kernel :func:`hertz_force` is in :mod:`lubedyn.lubrication.laws.collision`).

Everything here is plain Python on floats (``math``), run once at set-up; both
:mod:`lubrication` and :mod:`dynamics` call it.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from scipy.optimize import brentq
from scipy.special import beta, ellipe, ellipk

from ..errors import InputError, require_positive, unknown_choice

METHODS = ("exact", "hamrock_brewe")


def positive(key: str, value) -> float:
    """``float(value)``, or an :class:`InputError` naming ``key`` if it is not a finite number > 0."""
    value = float(value)
    if not (value > 0.0 and math.isfinite(value)):
        raise InputError(f"{key} = {value!r} must be a finite number > 0")
    return value


def reduced_modulus(E1: float, nu1: float, E2: float, nu2: float) -> float:
    """E* [Pa] with 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2 (Johnson 1985, eq. 4.22)."""
    positive("elastic modulus E1 [Pa]", E1)
    positive("elastic modulus E2 [Pa]", E2)
    for key, nu in (("Poisson ratio nu1", nu1), ("Poisson ratio nu2", nu2)):
        if not -1.0 < nu < 0.5:
            raise InputError(f"{key} = {nu!r} must lie in (-1, 0.5)")
    return 1.0 / ((1.0 - nu1**2) / E1 + (1.0 - nu2**2) / E2)


def relative_radii(curvatures_x, curvatures_y) -> tuple[float, float]:
    """Relative principal radii (R_x, R_y) [m] of two bodies from their principal curvatures [1/m]
    (convex positive, concave negative) in the rolling (x) and transverse (y) directions."""
    sx, sy = float(sum(curvatures_x)), float(sum(curvatures_y))
    if not (sx > 0.0 and sy > 0.0):
        raise InputError(
            f"contact curvature sums (x: {sx:g} 1/m, y: {sy:g} 1/m) must be > 0 (the surfaces must not conform)")
    return 1.0 / sx, 1.0 / sy


@dataclass(frozen=True)
class HertzPoint:
    """Hertzian point contact result (SI).  ``a`` is the semi-axis along the
    direction of the larger relative radius, ``b`` the other one."""

    a: float
    b: float
    p0: float
    approach: float
    load: float

    @property
    def ellipticity(self) -> float:
        return self.a / self.b

    @property
    def stiffness(self) -> float:
        """Tangent contact stiffness dW/d(delta) = 1.5 W / delta [N/m]."""
        return 1.5 * self.load / self.approach


def ellipse_radius_ratio(m: float) -> float:
    """R_a/R_b of the contact ellipse with parameter m = 1 - (b/a)^2, 0 < m < 1:
    (E(m)/(1 - m) - K(m))/(K(m) - E(m)) (Johnson 1985, eqs. 4.30-4.32)."""
    K, E = ellipk(m), ellipe(m)
    return (E / (1.0 - m) - K) / (K - E)


def _ratio_residual(m, ratio):
    return ellipse_radius_ratio(m) - ratio


def ellipticity_parameter(radius_ratio: float) -> float:
    """m = e^2 = 1 - (b/a)^2 of the contact ellipse for R_a/R_b = ``radius_ratio`` >= 1 (exact)."""
    if not radius_ratio >= 1.0:
        raise InputError(f"radius ratio R_a/R_b = {radius_ratio!r} must be >= 1")
    if radius_ratio - 1.0 < 1e-6:
        # series: R_a/R_b = 1 + 3m/4 + O(m^2); K - E cancels catastrophically here
        return 4.0 * (radius_ratio - 1.0) / 3.0
    if radius_ratio < 1.1:
        # below m ~ 1e-8 the residual is rounding noise (K - E ~ pi m/4) with spurious sign changes:
        # bracket from 1e-8 (root m ~ 4/3 (R_a/R_b - 1) > 1.3e-6 here)
        return brentq(_ratio_residual, 1e-8, 1.0 - 1e-15, args=(radius_ratio,), xtol=1e-16, rtol=1e-15)
    return brentq(_ratio_residual, 1e-14, 1.0 - 1e-15, args=(radius_ratio,), xtol=1e-16, rtol=1e-15)


def hamrock_brewe(radius_a: float, radius_b: float) -> tuple[float, float, float]:
    """Hamrock & Brewe (1983) fits (k, E, F) for R_a >= R_b: the ellipticity k = a/b =
    1.0339 (R_a/R_b)^0.636 and the elliptic integrals E = 1.0003 + 0.5968 R_b/R_a,
    F = 1.5277 + 0.6023 ln(R_a/R_b)."""
    return (1.0339 * (radius_a / radius_b) ** 0.636, 1.0003 + 0.5968 * radius_b / radius_a,
            1.5277 + 0.6023 * math.log(radius_a / radius_b))


def hamrock_brewe_radius_ratio(k: float) -> float:
    """R_a/R_b of the Hamrock-Brewe ellipticity fit solved for a given k = a/b (1 below k = 1.0339)."""
    return max(k / 1.0339, 1.0) ** (1 / 0.636)


def point_contact(load: float, radius_a: float, radius_b: float, e_star: float, method: str = "exact") -> HertzPoint:
    """Hertz point contact under ``load`` [N] with relative principal radii
    ``radius_a`` >= ``radius_b`` [m] (order is fixed here if reversed)."""
    if method not in METHODS:
        raise unknown_choice("hertz method", method, METHODS)
    load = positive("contact load [N]", load)
    Ra, Rb = positive("relative radius R_a [m]", radius_a), positive("relative radius R_b [m]", radius_b)
    e_star = positive("reduced modulus E* [Pa]", e_star)
    Ra, Rb = max(Ra, Rb), min(Ra, Rb)
    if method == "hamrock_brewe":
        k, Eb, F = hamrock_brewe(Ra, Rb)
        R = 1.0 / (1.0 / Ra + 1.0 / Rb)
        Ep = 2.0 * e_star
        a = (6.0 * k * k * Eb * load * R / (math.pi * Ep)) ** (1.0 / 3.0)
        b = (6.0 * Eb * load * R / (math.pi * k * Ep)) ** (1.0 / 3.0)
        delta = F * (9.0 / (2.0 * Eb * R) * (load / (math.pi * k * Ep)) ** 2) ** (1.0 / 3.0)
        return HertzPoint(a, b, 3.0 * load / (2.0 * math.pi * a * b), delta, load)
    m = ellipticity_parameter(Ra / Rb)
    if m < 1e-12:
        a = (3.0 * load * Ra / (4.0 * e_star)) ** (1.0 / 3.0)
        return HertzPoint(a, a, 3.0 * load / (2.0 * math.pi * a * a), a * a / Ra, load)
    K, E = ellipk(m), ellipe(m)
    a = (3.0 * load * Ra * (K - E) / (math.pi * e_star * m)) ** (1.0 / 3.0)
    b = a * math.sqrt(1.0 - m)
    p0 = 3.0 * load / (2.0 * math.pi * a * b)
    return HertzPoint(a, b, p0, p0 * b * K / e_star, load)


def hertz_constant(radius_a: float, radius_b: float, e_star: float, method: str = "exact") -> float:
    """K [N/m^1.5] of ``Q = K delta^1.5`` (the approach at Q = 1 N, to the power -3/2)."""
    return point_contact(1.0, radius_a, radius_b, e_star, method).approach ** -1.5


def series_constant(K1: float, K2: float) -> float:
    """K of two Hertz contacts in series (same load): (K1^-2/3 + K2^-2/3)^-3/2."""
    return (K1 ** (-2.0 / 3.0) + K2 ** (-2.0 / 3.0)) ** -1.5


def hunt_crossley_alpha(restitution: float, impact_speed: float) -> float:
    """alpha [s/m] of the Hunt-Crossley law for a restitution coefficient at an
    impact speed (Hunt & Crossley 1975: alpha = 3 (1 - e)/(2 v))."""
    if not 0.0 < restitution <= 1.0:
        raise InputError(f"restitution = {restitution!r} must lie in (0, 1]")
    return 1.5 * (1.0 - restitution) / positive("impact speed [m/s]", impact_speed)


@dataclass(frozen=True)
class HertzLine:
    """Hertzian line contact per unit length: half-width ``b`` [m], peak ``p0`` [Pa]."""

    b: float
    p0: float
    load_per_length: float


def line_contact(load_per_length: float, radius: float, e_star: float) -> HertzLine:
    """Hertz line contact of reduced radius ``radius`` [m] under ``load_per_length`` [N/m]
    (Johnson 1985, eq. 4.45: b = sqrt(4 W' R / (pi E*)), p0 = 2 W' / (pi b))."""
    load_per_length = positive("load per unit length [N/m]", load_per_length)
    radius = positive("reduced radius [m]", radius)
    e_star = positive("reduced modulus E* [Pa]", e_star)
    b = math.sqrt(4 * load_per_length * radius / (math.pi * e_star))
    return HertzLine(b, 2 * load_per_length / (math.pi * b), load_per_length)


@dataclass(frozen=True)
class HertzImpact:
    """The dry elastic impact of a sphere (Johnson 1985, sec. 11.4): ``approach`` delta* [m], ``force``
    F* [N], ``duration`` t_c [s], ``radius`` a* [m] and ``pressure`` p0* [Pa] (the Hertz maximum at F*)."""

    approach: float
    force: float
    duration: float
    radius: float
    pressure: float


def hertz_impact(radius: float, e_star: float, mass: float, speed: float) -> HertzImpact:
    """Hertz impact of effective ``radius`` R [m], reduced modulus ``e_star`` E* [Pa], effective ``mass``
    m [kg] at approach ``speed`` v [m/s] (Johnson 1985, eqs. 11.23-11.25).

    >>> h = hertz_impact(0.01, 1e11, 0.01, 1.0)
    >>> round(h.duration * 1.0 / h.approach, 4)
    2.9433
    """
    R = require_positive("impact radius [m]", radius)
    E = require_positive("impact e_star [Pa]", e_star)
    m = require_positive("impact mass [kg]", mass)
    v = require_positive("impact speed [m/s]", speed)
    delta = (15.0 * m * v * v / (16.0 * E * math.sqrt(R))) ** 0.4
    force = 4.0 / 3.0 * E * math.sqrt(R) * delta**1.5   # the Hertz force at that approach
    hp = point_contact(force, R, R, E)            # its contact radius and peak pressure
    return HertzImpact(approach=delta, force=force, duration=0.8 * float(beta(0.4, 0.5)) * delta / v,
                       radius=hp.a, pressure=hp.p0)
