"""Lubricant laws: viscosity eta(p) and density rho(p), with their derivatives.

All laws are frozen dataclasses in SI units, callable on numpy arrays of the
*gauge* pressure ``p`` [Pa] above ambient (negative values are clipped to zero
inside the pressure-dependent laws, so a Newton iterate that dips below
ambient cannot overflow).  Each law has ``__call__(p)`` and ``derivative(p)``
(d/dp) so that the Reynolds Newton solver can build its exact Jacobian.

Viscosity
---------
- :class:`ConstantViscosity`  eta = eta0
- :class:`Barus`              eta = eta0 exp(alpha p)
- :class:`Roelands`           eta = eta0 exp[(ln eta0 + 9.67)((1 + p/p0)^z - 1)],
  p0 = 1.96e8 Pa; ``z`` given, or chosen so that the low-pressure slope equals
  a Barus ``alpha``: z = alpha p0 / (ln eta0 + 9.67)  (Roelands 1966; Venner &
  Lubrecht 2000, eq. 2.12).

Shear thinning of the Poiseuille flow (Reynolds-Eyring)
-------------------------------------------------------
:class:`Lubricant` ``eyring_stress`` tau0 [Pa] (None: Newtonian).  An Eyring
fluid, shear rate (tau0/eta) sinh(tau/tau0), in pure rolling carries the
Poiseuille flow of a Newtonian one times the flow factor

    Phi(x) = 3 (x cosh x - sinh x) / x^3,   x = h |grad p| / (2 tau0)

(derived here from the sinh law: by symmetry tau = z |grad p| across the
film, z from mid-film; integrating the shear rate twice over the film gives
the flow; Phi -> 1 + x^2/10 as x -> 0.  The pure-rolling case of Conry, Wang &
Cusano 1987, "A Reynolds-Eyring equation for elastohydrodynamic lubrication
in line contacts", J. Tribol. 109, 648).  :func:`eyring_flow_factor`.

Density
-------
- :class:`Incompressible`     rho = rho0
- :class:`DowsonHigginson`    rho = rho0 (1 + a p / (1 + b p)),
  a = 0.6e-9 1/Pa, b = 1.7e-9 1/Pa (Dowson & Higginson 1966).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import InputError, require_positive

ROELANDS_P0 = 1.96e8  # Pa


def _pos(p):
    return np.maximum(np.asarray(p, dtype=float), 0.0)


@dataclass(frozen=True)
class ConstantViscosity:
    """Isoviscous lubricant. ``eta0`` [Pa s]."""

    eta0: float

    def __post_init__(self):
        require_positive("viscosity eta0 [Pa s]", self.eta0)

    is_constant = True
    pressure_viscosity = 0.0  #: d ln(eta)/dp at p = 0 [1/Pa]

    def __call__(self, p):
        return np.full_like(np.asarray(p, dtype=float), self.eta0)

    def derivative(self, p):
        return np.zeros_like(np.asarray(p, dtype=float))


@dataclass(frozen=True)
class Barus:
    """Barus law eta0 exp(alpha p). ``eta0`` [Pa s], ``alpha`` [1/Pa]."""

    eta0: float
    alpha: float

    is_constant = False

    def __post_init__(self):
        require_positive("viscosity eta0 [Pa s]", self.eta0)
        if self.alpha < 0:
            raise InputError(f"pressure-viscosity alpha [1/Pa] = {self.alpha!r} must be >= 0")

    @property
    def pressure_viscosity(self) -> float:
        """d ln(eta)/dp at p = 0 [1/Pa]: alpha."""
        return self.alpha

    def __call__(self, p):
        return self.eta0 * np.exp(self.alpha * _pos(p))

    def derivative(self, p):
        p = np.asarray(p, dtype=float)
        return np.where(p > 0, self.alpha * self(p), 0.0)


@dataclass(frozen=True)
class Roelands:
    """Roelands law; give ``z`` directly or ``alpha`` [1/Pa] to match Barus at p -> 0."""

    eta0: float
    z: float | None = None
    alpha: float | None = None
    p0: float = ROELANDS_P0

    is_constant = False

    def __post_init__(self):
        require_positive("viscosity eta0 [Pa s]", self.eta0)
        if (self.z is None) == (self.alpha is None):
            raise InputError("Roelands viscosity needs exactly one of 'z' or 'alpha'")
        if self.z is None:
            object.__setattr__(self, "z", self.alpha * self.p0 / (np.log(self.eta0) + 9.67))
        require_positive("Roelands z", self.z)

    @property
    def _c(self):
        return np.log(self.eta0) + 9.67

    @property
    def pressure_viscosity(self) -> float:
        """d ln(eta)/dp at p = 0 [1/Pa]: the ``alpha`` given, else z (ln eta0 + 9.67)/p0 (Roelands' slope)."""
        return self.alpha if self.alpha is not None else self.z * (np.log(self.eta0) + 9.67) / self.p0

    def __call__(self, p):
        return self.eta0 * np.exp(self._c * ((1.0 + _pos(p) / self.p0) ** self.z - 1.0))

    def derivative(self, p):
        p = np.asarray(p, dtype=float)
        q = _pos(p)
        d = self(q) * self._c * self.z / self.p0 * (1.0 + q / self.p0) ** (self.z - 1.0)
        return np.where(p > 0, d, 0.0)


@dataclass(frozen=True)
class Incompressible:
    """Constant density ``rho0`` [kg/m^3]."""

    rho0: float = 1.0

    is_constant = True

    def __post_init__(self):
        require_positive("density rho0 [kg/m^3]", self.rho0)

    def __call__(self, p):
        return np.full_like(np.asarray(p, dtype=float), self.rho0)

    def derivative(self, p):
        return np.zeros_like(np.asarray(p, dtype=float))


@dataclass(frozen=True)
class DowsonHigginson:
    """rho0 (1 + a p / (1 + b p)); ``rho0`` [kg/m^3], a, b [1/Pa] (Dowson & Higginson 1966, *Elasto-
    hydrodynamic Lubrication*: a = 0.6e-9, b = 1.7e-9 1/Pa for mineral oils, rho -> 1.353 rho0 as p -> inf)."""

    rho0: float
    a: float = 0.6e-9
    b: float = 1.7e-9

    is_constant = False

    def __post_init__(self):
        require_positive("density rho0 [kg/m^3]", self.rho0)

    def __call__(self, p):
        q = _pos(p)
        return self.rho0 * (1.0 + self.a * q / (1.0 + self.b * q))

    def derivative(self, p):
        p = np.asarray(p, dtype=float)
        q = _pos(p)
        return np.where(p > 0, self.rho0 * self.a / (1.0 + self.b * q) ** 2, 0.0)


# Phi(x) = 3 sum_{k>=1} 2k x^(2k-2)/(2k+1)!  and  Phi'(x)/x = 3 sum_{k>=2} 2k(2k-2) x^(2k-4)/(2k+1)!
_PHI_SERIES = (1.0, 1 / 10, 1 / 280, 1 / 15120, 1 / 1330560, 1 / 172972800)
_DPHI_SERIES = (1 / 5, 1 / 70, 1 / 2520, 1 / 166320, 1 / 17297280)
EYRING_X_CAP = 300.0  # Phi(300) ~ 1e126; above it Phi is held (derivative 0)


def eyring_flow_factor(x):
    """Reynolds-Eyring Poiseuille flow factor Phi(x) and Phi'(x)/x for x = h |grad p|/(2 tau0) >= 0.

    Phi = 3 (x cosh x - sinh x)/x^3, Phi'/x = 3 sinh x/x^3 - 3 Phi/x^2 (closed forms for
    x >= 0.5; their power series, to x^10, below it, where the closed forms cancel).
    x is held at :data:`EYRING_X_CAP`.  Returns ``(phi, dphi_over_x)``.
    """
    x = np.minimum(np.abs(np.asarray(x, dtype=float)), EYRING_X_CAP)
    x2 = x * x
    phi_s = np.polynomial.polynomial.polyval(x2, _PHI_SERIES)
    dphi_s = np.polynomial.polynomial.polyval(x2, _DPHI_SERIES)
    big = x >= 0.5
    xb = np.where(big, x, 1.0)
    phi_b = 3.0 * (xb * np.cosh(xb) - np.sinh(xb)) / xb**3
    dphi_b = 3.0 * np.sinh(xb) / xb**3 - 3.0 * phi_b / xb**2
    held = np.asarray(x) >= EYRING_X_CAP
    return np.where(big, phi_b, phi_s), np.where(held, 0.0, np.where(big, dphi_b, dphi_s))


@dataclass(frozen=True)
class Lubricant:
    """A lubricant: a viscosity law, a density law and, optionally, Eyring shear thinning.

    ``eyring_stress`` tau0 [Pa]: the Poiseuille flow of the EHL solver is the
    Newtonian one times :func:`eyring_flow_factor` (module docstring); None
    (default) is Newtonian.  Only :mod:`lubrication.ehl`'s finite-element
    solver uses it; the others refuse it.
    """

    viscosity: ConstantViscosity | Barus | Roelands
    density: Incompressible | DowsonHigginson = Incompressible()
    eyring_stress: float | None = None

    def __post_init__(self):
        if self.eyring_stress is not None:
            require_positive("lubricant eyring_stress [Pa]", self.eyring_stress)

    @property
    def is_constant(self) -> bool:
        """True when neither law depends on pressure and the fluid is Newtonian (the Reynolds problem is linear)."""
        return bool(self.viscosity.is_constant and self.density.is_constant and self.eyring_stress is None)

    @classmethod
    def newtonian(cls, eta0: float, rho0: float = 1.0) -> "Lubricant":
        """Isoviscous, incompressible lubricant."""
        return cls(ConstantViscosity(eta0), Incompressible(rho0))
