"""Lubricant laws: viscosity eta(p) and density rho(p), with their derivatives.

All laws are frozen dataclasses in SI units (their constructors also take strings with units, "50 mPa s":
:func:`lubedyn.lubrication.laws.units.si_fields`), callable on numpy arrays of the
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

Grease: Herschel-Bulkley Poiseuille flow
----------------------------------------
:class:`Lubricant` ``herschel_bulkley`` (a :class:`HerschelBulkleyFlow`: yield stress tau_y [Pa],
exponent n; None: Newtonian).  The viscosity law of the lubricant is then the consistency
phi(p) [Pa s^n] of tau = sign(D) (tau_y + phi |D|^n) (paper A eq. 26: ``Barus(phi0, alpha)``;
:meth:`Lubricant.from_grease`).  Derived here (slit flow of a Herschel-Bulkley fluid, the
Buckingham-Reiner problem for n = 1; e.g. Bird, Dai & Yarusso 1983, Rev. Chem. Eng. 1, 1, for
general n): walls at rest at z = +-h/2, pressure gradient G = |grad p|, stress |tau| = G |z|
(symmetric about mid-film), wall stress T_w = G h/2.  Where |tau| <= tau_y the fluid is a rigid
plug, |z| <= h_p = tau_y/G; outside, |du/dz| = ((G|z| - tau_y)/phi)^m, m = 1/n.  The flow per unit
width (Rabinowitsch-Mooney form q = (2/G^2) int_0^T_w tau D(tau) dtau) is

    q = (2 phi^-m/G^2) (T_w - tau_y)^(m+1) [(T_w - tau_y)/(m+2) + tau_y/(m+1)]   (T_w > tau_y)
    q = 0                                                                       (T_w <= tau_y)

and, relative to the Newtonian flow G h^3/(12 phi) with phi's SI number read as Pa s,

    Phi_HB = 3 (T_w/phi)^(m-1) F(xi),   xi = tau_y/T_w,
    F(xi)  = (1 - xi)^(m+1) [(1 - xi)/(m+2) + xi/(m+1)]   (0 for xi >= 1),
    F'(xi) = -(1 - xi)^m (m + xi)/(m+1).

n = 1: Phi_HB = 1 - 3 xi/2 + xi^3/2 (Buckingham-Reiner for the slit); tau_y = 0, n = 1: Phi_HB = 1.
For n != 1 Phi_HB is an effective factor that carries units s^(n-1) (q ~ |grad p|^(1/n) h^(m+2)
phi^-m): k = rho h^3/(12 phi) Phi_HB ~ phi^-m.  Its derivatives (the Newton Jacobian):
dPhi/dT_w = 3 (T_w/phi)^(m-1)/T_w [(m-1) F - xi F'],  d ln Phi/d ln phi = 1 - m.
In a rolling contact with sliding the flux is taken as rho h u_m (Couette, both walls' mean
speed) plus this pressure flow, as the Eyring option does: exact in pure rolling (in the frame
moving at u_m the walls are at rest), an approximation with sliding, where a nonlinear fluid's
Couette and Poiseuille parts do not superpose (Wada & Tsukijima 1985; Jonkisz & Krzeminski-Freda
1982 solve the coupled profile with the plug off-centre).  No regularisation: the law is exact,
Phi_HB and its derivative are continuous at xi = 1 (both vanish like (1 - xi)^m).  But Phi_HB = 0
in a plug (and -> 0 as |grad p| -> 0 for n < 1), which leaves rows of the EHL Jacobian with no
pressure dependence (incompressible: exactly singular where the start has p = 0).  The optional
regularisation ``creep`` eps: the shear rate D_HB(tau) + eps tau/phi, a Newtonian creep of
viscosity phi/eps in parallel; since q = (2/G^2) int tau D dtau is linear in D, the flow factor is
exactly Phi_HB + eps (same derivative in T_w; d ln Phi/d ln phi = (1 - m) Phi_HB/(Phi_HB + eps)).
Papanastasiou's regularisation (:mod:`lubedyn.lubrication.laws.grease`) would not do: for n < 1 the phi D^n
term still dominates at small D and the conductance still vanishes.
:func:`herschel_bulkley_flow_factor`.

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
from .units import si_fields

ROELANDS_P0 = 1.96e8  # Pa


def _pos(p):
    return np.maximum(np.asarray(p, dtype=float), 0.0)


@dataclass(frozen=True)
class ConstantViscosity:
    """Isoviscous lubricant. ``eta0`` [Pa s]."""

    eta0: float

    def __post_init__(self):
        si_fields(self, eta0="dynamic viscosity")
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
        si_fields(self, eta0="dynamic viscosity", alpha="inverse pressure")
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
        si_fields(self, eta0="dynamic viscosity", alpha="inverse pressure", p0="pressure")
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
        si_fields(self, rho0="density")
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
        si_fields(self, rho0="density", a="inverse pressure", b="inverse pressure")
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


HB_PHI_CAP = 1e100  # Phi_HB is held there (derivatives 0): n > 1 at vanishing stress, or phi underflow


@dataclass(frozen=True)
class HerschelBulkleyFlow:
    """Herschel-Bulkley Poiseuille flow of a grease (module docstring): ``yield_stress`` tau_y [Pa] >= 0,
    ``exponent`` n in (0, 2] (the range :class:`lubedyn.lubrication.laws.grease.Grease` accepts).  The
    consistency phi(p) [Pa s^n] is the lubricant's viscosity law.  ``creep`` eps >= 0 (default 0, the
    exact law): the regularisation Phi = Phi_HB + eps (module docstring), a Newtonian creep of
    viscosity phi/eps in parallel, so that plugs and vanishing pressure gradients keep a small
    Poiseuille conductance and the Newton Jacobian stays regular."""

    yield_stress: float = 0.0
    exponent: float = 1.0
    creep: float = 0.0

    def __post_init__(self):
        ty = float(self.yield_stress)
        if not (ty >= 0.0 and np.isfinite(ty)):
            raise InputError(f"lubricant herschel_bulkley.yield_stress [Pa] = {self.yield_stress!r} "
                             "must be a finite number >= 0")
        n = float(self.exponent)
        if not 0.0 < n <= 2.0:
            raise InputError(f"lubricant herschel_bulkley.exponent n = {self.exponent!r} must lie in (0, 2]")
        c = float(self.creep)
        if not (0.0 <= c < 1.0):
            raise InputError(f"lubricant herschel_bulkley.creep = {self.creep!r} must lie in [0, 1) "
                             "(0: the exact law; e.g. 1e-6: a Newtonian creep of viscosity phi/creep)")

    def flow_factor(self, wall_stress, consistency):
        """:func:`herschel_bulkley_flow_factor` with this yield stress and exponent."""
        return herschel_bulkley_flow_factor(wall_stress, consistency, self.yield_stress, self.exponent)


def herschel_bulkley_flow_factor(wall_stress, consistency, yield_stress, exponent):
    """Herschel-Bulkley Poiseuille flow factor (module docstring) at wall stress T_w = h |grad p|/2 [Pa]
    and consistency phi [Pa s^n].

    Returns ``(phi_hb, dphi_dT)``: Phi_HB = 3 (T_w/phi)^(m-1) F(tau_y/T_w), m = 1/n, and dPhi_HB/dT_w
    [1/Pa] = 3 (T_w/phi)^(m-1)/T_w [(m-1) F - xi F'].  Phi_HB = 0 where T_w <= tau_y (plug across the
    film); evaluated through logarithms, held at :data:`HB_PHI_CAP` (derivative 0 there); at T_w = 0
    with tau_y = 0 it is its limit (0 for n < 1, 1 for n = 1, the cap for n > 1), derivative 0.
    d ln Phi_HB/d ln phi = 1 - m is the caller's (k = rho h^3/(12 phi) Phi_HB ~ phi^-m)."""
    T = np.abs(np.asarray(wall_stress, dtype=float))
    eta = np.asarray(consistency, dtype=float)
    m = 1.0 / float(exponent)
    ty = float(yield_stress)
    flowing = T > ty
    Ts = np.where(flowing & (T > 0), T, 1.0)
    xi = np.where(flowing, ty / Ts, 0.0)
    one = 1.0 - xi
    F = one ** (m + 1.0) * (one / (m + 2.0) + xi / (m + 1.0))
    dF = -one**m * (m + xi) / (m + 1.0)
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
        if m == 1.0:
            log_ratio = np.zeros(np.broadcast(T, eta).shape)
        else:
            log_ratio = (m - 1.0) * (np.log(Ts) - np.log(eta))
            log_ratio = np.where(np.isnan(log_ratio), np.inf if m < 1.0 else -np.inf, log_ratio)
        log_cap = np.log(HB_PHI_CAP)
        pre = 3.0 * np.exp(np.minimum(log_ratio, log_cap))
        phi = pre * F
        dphi = pre / Ts * ((m - 1.0) * F - xi * dF)
    held = (log_ratio >= log_cap) | (phi >= HB_PHI_CAP)
    phi = np.minimum(phi, HB_PHI_CAP)
    zero_stress = ~(T > 0)
    if ty == 0.0 and m != 1.0:  # T_w = 0, no yield stress: the power law's limit
        phi = np.where(zero_stress, 0.0 if m > 1.0 else HB_PHI_CAP, phi)
    phi = np.where(flowing | ((ty == 0.0) & zero_stress), phi, 0.0)
    dphi = np.where(flowing & ~held & ~zero_stress & np.isfinite(dphi), dphi, 0.0)
    return phi, dphi


@dataclass(frozen=True)
class Lubricant:
    """A lubricant: a viscosity law, a density law and, optionally, Eyring shear thinning.

    ``eyring_stress`` tau0 [Pa]: the Poiseuille flow of the EHL solver is the
    Newtonian one times :func:`eyring_flow_factor` (module docstring); None
    (default) is Newtonian.  ``herschel_bulkley``: a :class:`HerschelBulkleyFlow`
    (grease; the viscosity law is then the consistency phi(p) [Pa s^n]), the
    Poiseuille flow times :func:`herschel_bulkley_flow_factor`; at most one of
    the two.  Only :mod:`lubedyn.lubrication.ehl`'s finite-element solver uses them;
    the others refuse them.
    """

    viscosity: ConstantViscosity | Barus | Roelands
    density: Incompressible | DowsonHigginson = Incompressible()
    eyring_stress: float | None = None
    herschel_bulkley: HerschelBulkleyFlow | None = None

    def __post_init__(self):
        si_fields(self, eyring_stress="pressure")
        if self.eyring_stress is not None:
            require_positive("lubricant eyring_stress [Pa]", self.eyring_stress)
        if self.herschel_bulkley is not None:
            if not isinstance(self.herschel_bulkley, HerschelBulkleyFlow):
                raise InputError(f"lubricant herschel_bulkley = {self.herschel_bulkley!r} must be a "
                                 "HerschelBulkleyFlow(yield_stress, exponent) or None")
            if self.eyring_stress is not None:
                raise InputError(f"lubricant eyring_stress = {self.eyring_stress!r} with herschel_bulkley: "
                                 "choose one non-Newtonian flow (Eyring or Herschel-Bulkley), not both")

    @property
    def is_newtonian(self) -> bool:
        """True without Eyring or Herschel-Bulkley flow."""
        return self.eyring_stress is None and self.herschel_bulkley is None

    @property
    def is_constant(self) -> bool:
        """True when neither law depends on pressure and the fluid is Newtonian (the Reynolds problem is linear)."""
        return bool(self.viscosity.is_constant and self.density.is_constant and self.is_newtonian)

    @classmethod
    def from_grease(cls, grease, density=None) -> "Lubricant":
        """A Herschel-Bulkley lubricant of a :class:`lubedyn.lubrication.laws.grease.Grease`: viscosity law
        Barus(phi0, alpha) (the consistency, paper A eq. 26), flow HerschelBulkleyFlow(tau_y, n)."""
        return cls(Barus(grease.consistency, grease.pressure_viscosity), density or Incompressible(),
                   herschel_bulkley=HerschelBulkleyFlow(grease.yield_stress, grease.exponent))

    @classmethod
    def newtonian(cls, eta0: float | str, rho0: float | str = 1.0) -> "Lubricant":
        """Isoviscous, incompressible lubricant (numbers in SI or strings with units: ``newtonian("50 mPa s")``)."""
        return cls(ConstantViscosity(eta0), Incompressible(rho0))
