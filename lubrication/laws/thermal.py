r"""Viscosity against temperature: the Walther (Ubbelohde-Walther) line of ASTM D341.

A petroleum oil's kinematic viscosity nu [mm^2/s] plots as a straight line in the double-log chart of
ASTM D341 (Standard Practice for Viscosity-Temperature Equations and Charts for Liquid Petroleum or
Hydrocarbon Products)::

    log10 log10(nu + 0.7) = A - B log10(T),    T [K] = t [C] + 273.15

two measured points (t1, nu1), (t2, nu2) fix A and B::

    B = (Z1 - Z2) / (log10 T2 - log10 T1),   A = Z1 + B log10 T1,   Z = log10 log10(nu + 0.7)

and nu(t) = 10^(10^(A - B log10 T)) - 0.7.  The standard's 2020 edition adds a small correction to the
0.7 below about 2 mm^2/s; above it (every oil of a bearing) the 0.7 form is the standard's.  The
dynamic viscosity is eta = rho nu (the density's own change with temperature, about 0.07 %/K for a
mineral oil, is left out and said so where this is used).

Checked (tests/test_laws_thermal.py) against a worked example of the standard's two-point method
published with its constants: (40 C, 32 mm^2/s) and (100 C, 5.4 mm^2/s) give A = 9.5259, B = 3.7449
(with T = t + 273) and 8.5 mm^2/s at 80 C.

Why a bearing model needs it: the films (Dowson-Toyoda, Hamrock-Dowson), the film's elastic traction slope
2 G b^2/(u_e h), the pocket and guide-land films all scale with the base oil's viscosity, which falls by a
factor of about 15 from 15 to 70 C for an ISO VG 68 mineral oil (0.26 -> 0.017 Pa s at 870 kg/m^3, 0.1 Pa s at 30 C): a
temperature that changes only the grease's Herschel-Bulkley constants and not its base oil leaves most of
the lubricant's temperature out of a run.
"""
from __future__ import annotations

import math

from ..errors import InputError
from .contact import positive

KELVIN = 273.15          #: t [C] -> T [K]
WALTHER_SHIFT = 0.7      #: ASTM D341's constant in log log(nu + 0.7), nu in mm^2/s
#: the standard's range of use (its charts run from -70 to 370 C); nothing outside is extrapolated
RANGE_C = (-70.0, 370.0)


def _z(nu_mm2s: float) -> float:
    return math.log10(math.log10(nu_mm2s + WALTHER_SHIFT))


def walther_constants(t1_c: float, nu1: float, t2_c: float, nu2: float) -> tuple[float, float]:
    """(A, B) of the Walther line through (``t1_c`` [C], ``nu1`` [m^2/s]) and (``t2_c``, ``nu2``):
    log10 log10(nu [mm^2/s] + 0.7) = A - B log10(t + 273.15)."""
    positive("kinematic viscosity nu1 [m^2/s]", nu1)
    positive("kinematic viscosity nu2 [m^2/s]", nu2)
    for name, t in (("t1 [C]", t1_c), ("t2 [C]", t2_c)):
        if not RANGE_C[0] <= t <= RANGE_C[1]:
            raise InputError(f"Walther temperature {name} = {t!r} is outside ASTM D341's {RANGE_C[0]:g} to "
                             f"{RANGE_C[1]:g} C")
    if t1_c == t2_c:
        raise InputError(f"Walther line: the two temperatures are equal ({t1_c!r} C); give two different ones")
    lt1, lt2 = math.log10(t1_c + KELVIN), math.log10(t2_c + KELVIN)
    z1, z2 = _z(nu1 * 1e6), _z(nu2 * 1e6)
    b = (z1 - z2) / (lt2 - lt1)
    return z1 + b * lt1, b


def walther_kinematic(t_c: float, t1_c: float, nu1: float, t2_c: float, nu2: float) -> float:
    """Kinematic viscosity [m^2/s] at ``t_c`` [C] on the Walther line through two points (SI viscosities);
    exactly ``nu1`` at ``t1_c`` and ``nu2`` at ``t2_c`` (no round trip through the logarithms there)."""
    a, b = walther_constants(t1_c, nu1, t2_c, nu2)
    if not RANGE_C[0] <= t_c <= RANGE_C[1]:
        raise InputError(f"Walther temperature [C] = {t_c!r} is outside ASTM D341's {RANGE_C[0]:g} to "
                         f"{RANGE_C[1]:g} C")
    if t_c == t1_c:
        return float(nu1)
    if t_c == t2_c:
        return float(nu2)
    return (10.0 ** (10.0 ** (a - b * math.log10(t_c + KELVIN))) - WALTHER_SHIFT) * 1e-6


def walther_dynamic(t_c: float, t_ref_c: float, eta_ref: float, t2_c: float, nu2: float, density: float) -> float:
    """Dynamic viscosity [Pa s] at ``t_c`` [C] of an oil of viscosity ``eta_ref`` [Pa s] at ``t_ref_c``
    and kinematic viscosity ``nu2`` [m^2/s] at ``t2_c``, of constant ``density`` [kg/m^3]:
    rho nu(t) on the Walther line; exactly ``eta_ref`` at ``t_ref_c``."""
    rho = positive("oil density [kg/m^3]", density)
    positive("reference viscosity [Pa s]", eta_ref)
    if t_c == t_ref_c:
        return float(eta_ref)
    return rho * walther_kinematic(t_c, t_ref_c, eta_ref / rho, t2_c, nu2)
