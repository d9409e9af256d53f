r"""Hertz contact of elastic bodies: point (circular, elliptical) and line contacts.

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
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq
from scipy.special import ellipe, ellipk

from .errors import InputError, require_positive

METHODS = ("exact", "hamrock_brewe")


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


def _ratio_residual(m, ratio):
    K, E = ellipk(m), ellipe(m)
    return (E / (1.0 - m) - K) / (K - E) - ratio


def ellipticity_parameter(radius_ratio: float) -> float:
    """m = e^2 = 1 - (b/a)^2 of the contact ellipse for R_a/R_b = ``radius_ratio`` >= 1."""
    if radius_ratio < 1.0:
        raise InputError(f"radius ratio R_a/R_b = {radius_ratio!r} must be >= 1")
    if radius_ratio - 1.0 < 1e-5:
        # series: R_a/R_b = 1 + 3m/4 + O(m^2); K - E cancels catastrophically here
        return 4.0 * (radius_ratio - 1.0) / 3.0
    return brentq(_ratio_residual, 1e-14, 1.0 - 1e-14, args=(radius_ratio,), xtol=1e-15, rtol=1e-15)


def point_contact(load: float, radius_a: float, radius_b: float, e_star: float, method: str = "exact") -> HertzPoint:
    """Hertz point contact under ``load`` [N] with relative principal radii
    ``radius_a`` >= ``radius_b`` [m] (order is fixed here if reversed)."""
    if method not in METHODS:
        from .errors import unknown_choice

        raise unknown_choice("hertz method", method, METHODS)
    require_positive("contact load [N]", load)
    require_positive("relative radius R_a [m]", radius_a)
    require_positive("relative radius R_b [m]", radius_b)
    require_positive("reduced modulus E* [Pa]", e_star)
    Ra, Rb = max(radius_a, radius_b), min(radius_a, radius_b)
    if method == "hamrock_brewe":
        k = 1.0339 * (Ra / Rb) ** 0.636
        Ebar = 1.0003 + 0.5968 * Rb / Ra
        F = 1.5277 + 0.6023 * np.log(Ra / Rb)
        R = 1.0 / (1.0 / Ra + 1.0 / Rb)
        Ep = 2.0 * e_star
        a = (6 * k**2 * Ebar * load * R / (np.pi * Ep)) ** (1 / 3)
        b = (6 * Ebar * load * R / (np.pi * k * Ep)) ** (1 / 3)
        delta = F * (9 / (2 * Ebar * R) * (load / (np.pi * k * Ep)) ** 2) ** (1 / 3)
        return HertzPoint(a, b, 3 * load / (2 * np.pi * a * b), delta, load)
    m = ellipticity_parameter(Ra / Rb)
    if m == 0.0:
        a = (3 * load * Ra / (4 * e_star)) ** (1 / 3)
        return HertzPoint(a, a, 3 * load / (2 * np.pi * a * a), a * a / Ra, load)
    K, E = ellipk(m), ellipe(m)
    a = (3 * load * Ra * (K - E) / (np.pi * e_star * m)) ** (1 / 3)
    b = a * np.sqrt(1.0 - m)
    p0 = 3 * load / (2 * np.pi * a * b)
    return HertzPoint(a, b, p0, p0 * b * K / e_star, load)


@dataclass(frozen=True)
class HertzLine:
    """Hertzian line contact per unit length: half-width ``b`` [m], peak ``p0`` [Pa]."""

    b: float
    p0: float
    load_per_length: float


def line_contact(load_per_length: float, radius: float, e_star: float) -> HertzLine:
    """Hertz line contact of reduced radius ``radius`` [m] under ``load_per_length`` [N/m]."""
    require_positive("load per unit length [N/m]", load_per_length)
    require_positive("reduced radius [m]", radius)
    require_positive("reduced modulus E* [Pa]", e_star)
    b = np.sqrt(4 * load_per_length * radius / (np.pi * e_star))
    return HertzLine(b, 2 * load_per_length / (np.pi * b), load_per_length)
