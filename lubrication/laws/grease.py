r"""Grease rheology (Herschel-Bulkley), its temperature table, the two readings of the plastic viscosity,
and the film thickness of a grease-lubricated line contact.  Paper A: Wu, Xu & Deng 2018, eq. 26 and
Table 2; the readings chosen where the paper is ambiguous are given below with their reasons.

Herschel-Bulkley (Herschel & Bulkley 1926, Kolloid-Z. 39, 291; paper A eq. 26), sign-odd::

    tau(D) = sign(D) (tau_y + phi |D|^n),    phi = phi0 exp(alpha p)   (Barus, eq. 26's phi)

tau_y [Pa] yield stress, phi [Pa s^n] plastic viscosity ("consistency"), n power-law exponent, D [1/s]
shear rate.  At D = 0 the law is multivalued (|tau| <= tau_y); :func:`hb_stress` returns 0 there, and
an optional regularisation rate D_r (Papanastasiou 1987, J. Rheol. 31, 385) replaces tau_y by
tau_y (1 - exp(-|D|/D_r)), continuous through D = 0 (D_r = 0: the exact law).  The apparent viscosity
tau/D = tau_y/|D| + phi |D|^(n-1) (:func:`hb_apparent_viscosity`).

Temperature (Table 2 gives 15, 30, 50 and 70 C): :func:`grease_at` interpolates piecewise between the
two neighbouring table temperatures, *log-linearly* in tau_y and phi (both fall roughly exponentially
with temperature, as viscosities do) and *linearly* in n; it reproduces the table at its temperatures
and refuses temperatures outside 15-70 C (no extrapolation of a four-point table).

The readings of phi (the paper's eqs. 12, 25, 34-35, 40 and 44 use phi, in Pa s^n, as a Newtonian
viscosity in Pa s):

- ``"base_oil"`` (default): films and Newtonian traction use a base-oil viscosity (given; paper A does not
  give one, so it is assumed in the parameter module); the grease enters through eq. 26's traction only.
- ``"apparent"``: the apparent viscosity tau_y/D + phi D^(n-1) at the contact's shear rate (for a film
  :func:`apparent_film` solves D = u_m/h_c self-consistently; for traction D = u_s/h).
- ``"paper"``: phi0's number taken as Pa s, literally as the paper's equations do.

Why ``"base_oil"`` is the default: (1) fully flooded grease EHL films at rolling speeds of metres per
second are base-oil films to within tens of per cent (the thickener is largely excluded from the inlet;
Kauzlarich & Greenwood 1972, ASLE Trans. 15, 269; Cann, e.g. Tribol. Int. 1996); (2) phi0 = 8.44 taken
as Pa s gives raceway films of 115-191 um, which no bearing runs on; (3) the Table 2 fits come
from rheometers (shear rates up to about 1e3-1e4 1/s), and extrapolated to the contacts' 1e5-1e7 1/s
their apparent viscosity falls below any plausible base oil (lithium at 30 C: 0.0043 Pa s at 1e6 1/s,
0.0008 at 1e7), while a real grease tends to its base oil's viscosity at high shear rate
(Sisko/Bingham-type behaviour).  The cost of the default: the film no longer depends on the grease, so
Figs. 14 and 16 respond only through traction.  The other readings are options, and the choice
reverses the greases' ranking (tests/test_laws_grease.py): by phi0 (``"paper"``) calcium > lithium >
polyurea at 30 C; by apparent viscosity at 1e6 1/s polyurea > calcium > lithium.

Film of a grease line contact (:func:`grease_line_film`).  The grease film model paper A cites is lost
(its reference list stops at [3]; Kauzlarich & Greenwood 1972 is a guess).  Used here: the Newtonian
line-contact formulas of :mod:`.film` -- Dowson & Toyoda (1979) central film or Moes (1992) -- with the
viscosity of the chosen reading and the grease's pressure-viscosity coefficient alpha.  For tau_y = 0,
n = 1 (a Newtonian "grease" phi0 = eta) every reading that uses the grease gives exactly those formulas'
film (tested; at paper A's most loaded cone contact at 2.4 krpm, phi0 = 0.1 Pa s, Dowson-Toyoda gives
5.4 um).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from numba import njit

from ..errors import ConvergenceError, InputError, unknown_choice
from . import film as F
from .contact import positive
from .jit import INLINE

READINGS = ("base_oil", "apparent", "paper")
LINE_FILMS = ("dowson_toyoda", "moes")
TABLE_RANGE_C = (15.0, 70.0)  #: Table 2's temperatures [C]: nothing outside is extrapolated


# ---------------------------------------------------------------- numba leaves


@njit(**INLINE)
def hb_stress(shear_rate, yield_stress, consistency, exponent, yield_rate):
    """Herschel-Bulkley shear stress [Pa], sign-odd: sign(D) (tau_y r + phi |D|^n) with r = 1
    (``yield_rate`` D_r = 0) or r = 1 - exp(-|D|/D_r) (Papanastasiou); 0 at D = 0."""
    d = abs(shear_rate)
    if d == 0.0:
        return 0.0
    ty = yield_stress if yield_rate <= 0.0 else yield_stress * -math.expm1(-d / yield_rate)
    tau = ty + consistency * d**exponent
    return tau if shear_rate > 0.0 else -tau


@njit(**INLINE)
def hb_apparent_viscosity(shear_rate, yield_stress, consistency, exponent):
    """Apparent viscosity tau/D = tau_y/|D| + phi |D|^(n-1) [Pa s] (D != 0)."""
    d = abs(shear_rate)
    return yield_stress / d + consistency * d ** (exponent - 1.0)


@njit(**INLINE)
def barus_consistency(consistency, pressure_viscosity, pressure):
    """phi0 exp(alpha p) [Pa s^n] (paper A eq. 26; gauge pressure below 0 is clipped)."""
    return consistency * math.exp(pressure_viscosity * max(pressure, 0.0))


# ---------------------------------------------------------------- a grease


@dataclass(frozen=True)
class Grease:
    """A Herschel-Bulkley grease (SI): ``yield_stress`` tau_y [Pa], ``consistency`` phi0 [Pa s^n] at
    atmospheric pressure, ``exponent`` n, ``pressure_viscosity`` alpha [1/Pa] of phi = phi0 exp(alpha p);
    ``name`` and ``temperature_c`` [C] say where it comes from."""

    yield_stress: float
    consistency: float
    exponent: float
    pressure_viscosity: float = 0.0
    name: str = "grease"
    temperature_c: float | None = None

    def __post_init__(self):
        if not (self.yield_stress >= 0.0 and math.isfinite(self.yield_stress)):
            raise InputError(f"grease yield_stress [Pa] = {self.yield_stress!r} must be a finite number >= 0")
        positive("grease consistency phi0 [Pa s^n]", self.consistency)
        if not 0.0 < self.exponent <= 2.0:
            raise InputError(f"grease exponent n = {self.exponent!r} must lie in (0, 2]")
        if not (self.pressure_viscosity >= 0.0 and math.isfinite(self.pressure_viscosity)):
            raise InputError(f"grease pressure_viscosity alpha [1/Pa] = {self.pressure_viscosity!r} "
                             "must be a finite number >= 0")

    def consistency_at(self, pressure: float) -> float:
        """phi = phi0 exp(alpha p) [Pa s^n]."""
        return barus_consistency(self.consistency, self.pressure_viscosity, pressure)

    def stress(self, shear_rate: float, pressure: float = 0.0, yield_rate: float = 0.0) -> float:
        """tau [Pa] of eq. 26 at shear rate ``shear_rate`` [1/s] and gauge ``pressure`` [Pa]."""
        return hb_stress(shear_rate, self.yield_stress, self.consistency_at(pressure), self.exponent, yield_rate)

    def apparent_viscosity(self, shear_rate: float, pressure: float = 0.0) -> float:
        """tau_y/|D| + phi |D|^(n-1) [Pa s]."""
        positive("grease shear rate [1/s]", abs(shear_rate))
        return hb_apparent_viscosity(shear_rate, self.yield_stress, self.consistency_at(pressure), self.exponent)

    def viscosity(self, reading: str = "base_oil", shear_rate: float | None = None,
                  base_oil_viscosity: float | None = None) -> float:
        """The Newtonian viscosity [Pa s] a film or eq. 12 uses under ``reading`` (module docstring):
        the base oil's, the apparent one at ``shear_rate`` [1/s], or phi0's number ("paper")."""
        if reading not in READINGS:
            raise unknown_choice("grease viscosity reading", reading, READINGS)
        if reading == "base_oil":
            if base_oil_viscosity is None:
                raise InputError("base_oil_viscosity [Pa s] = None: the 'base_oil' reading needs a base-oil viscosity")
            return positive("base_oil_viscosity [Pa s]", base_oil_viscosity)
        if reading == "apparent":
            if shear_rate is None:
                raise InputError("shear_rate [1/s] = None: the 'apparent' reading needs the contact's shear rate")
            return self.apparent_viscosity(shear_rate)
        return self.consistency


def grease_at(rows, temperature_c: float, pressure_viscosity: float = 0.0, name: str = "grease") -> Grease:
    """The grease of a Table-2-like ``rows`` [(T [C], tau_y [Pa], phi [Pa s^n], n), ...] at
    ``temperature_c`` [C]: log-linear in tau_y and phi, linear in n between the neighbouring rows;
    outside the table's temperatures an :class:`InputError`."""
    rows = sorted((float(t), float(ty), float(ph), float(n)) for t, ty, ph, n in rows)
    t = float(temperature_c)
    lo, hi = rows[0][0], rows[-1][0]
    if not lo <= t <= hi:  # also refuses nan
        raise InputError(f"grease temperature [C] = {temperature_c!r} is outside the table of {name!r}: "
                         f"allowed {lo:g}-{hi:g} C")
    for (t0, ty0, ph0, n0), (t1, ty1, ph1, n1) in zip(rows, rows[1:]):
        if t <= t1:
            break
    for tr, tyr, phr, nr in rows:
        if t == tr:  # a table temperature: the table's numbers, no round-off
            return Grease(tyr, phr, nr, pressure_viscosity, name, t)
    w = (t - t0) / (t1 - t0)
    ty = ty0 if ty0 == ty1 else math.exp((1 - w) * math.log(ty0) + w * math.log(ty1))
    ph = math.exp((1 - w) * math.log(ph0) + w * math.log(ph1))
    return Grease(ty, ph, (1 - w) * n0 + w * n1, pressure_viscosity, name, t)


# ---------------------------------------------------------------- films


@dataclass(frozen=True)
class GreaseFilm:
    """A grease film: ``central`` h_c [m], the Newtonian ``viscosity`` [Pa s] it was computed with, and
    the ``shear_rate`` [1/s] that viscosity belongs to (None unless the reading is "apparent")."""

    central: float
    viscosity: float
    shear_rate: float | None
    iterations: int = 0


def newtonian_line_film(viscosity, speed, load_per_length, radius, e_prime, alpha, formula="dowson_toyoda"):
    """Central film h_c [m] of a Newtonian line contact (:mod:`.film`): Dowson-Toyoda or Moes, with
    U = eta u_m/(E' R), W = w/(E' R), G = alpha E'; Moes' M = W (2U)^-1/2, L = G (2U)^1/4."""
    if formula not in LINE_FILMS:
        raise unknown_choice("line film formula", formula, LINE_FILMS)
    U = viscosity * speed / (e_prime * radius)
    W, G = load_per_length / (e_prime * radius), alpha * e_prime
    if formula == "dowson_toyoda":
        return radius * F.dowson_toyoda_central(U, G, W)
    return radius * math.sqrt(2 * U) * float(F.moes_line_central(W / math.sqrt(2 * U), G * (2 * U) ** 0.25))


def apparent_film(grease: Grease, speed: float, film_of_viscosity, shear_rate: float | None = None,
                  tol: float = 1e-13, max_iter: int = 200) -> GreaseFilm:
    """The film of the "apparent" reading: eta = tau_y/D + phi0 D^(n-1) at D = ``shear_rate`` if given,
    else at the film's own rolling shear-rate scale D = u_m/h_c, solved by fixed-point iteration
    (a contraction: d ln h/d ln eta <= 0.7 for the EHL formulas and d ln eta/d ln h <= 1).
    ``film_of_viscosity(eta) -> h_c`` [m]."""
    if shear_rate is not None:
        eta = grease.apparent_viscosity(shear_rate)
        return GreaseFilm(film_of_viscosity(eta), eta, float(shear_rate), 0)
    speed = positive("entrainment speed u_m [m/s]", speed)
    h = film_of_viscosity(grease.consistency)
    for it in range(1, max_iter + 1):
        D = speed / h
        eta = grease.apparent_viscosity(D)
        h_new = film_of_viscosity(eta)
        if abs(h_new - h) <= tol * h_new:
            return GreaseFilm(h_new, eta, speed / h_new, it)
        h = h_new
    raise ConvergenceError(f"apparent-viscosity film: no fixed point after {max_iter} iterations "
                           f"(h_c {h:.6g} m, change {abs(h_new - h) / h_new:.3g})")


def grease_line_film(grease: Grease, reading: str, speed: float, load_per_length: float, radius: float,
                     e_prime: float, base_oil_viscosity: float | None = None, formula: str = "dowson_toyoda",
                     shear_rate: float | None = None) -> GreaseFilm:
    """Central film of a grease line contact: :func:`newtonian_line_film` (``formula``) with the viscosity
    of ``reading`` and alpha of the grease.  ``speed`` u_m [m/s], ``load_per_length`` [N/m], reduced
    ``radius`` R [m], ``e_prime`` E' = 2 E* [Pa]."""
    if reading not in READINGS:
        raise unknown_choice("grease viscosity reading", reading, READINGS)
    speed = positive("entrainment speed u_m [m/s]", speed)
    w = positive("load per unit length [N/m]", load_per_length)
    R, Ep = positive("reduced radius [m]", radius), positive("E' [Pa]", e_prime)
    if formula not in LINE_FILMS:
        raise unknown_choice("line film formula", formula, LINE_FILMS)

    def film(eta):
        return newtonian_line_film(eta, speed, w, R, Ep, grease.pressure_viscosity, formula)

    if reading == "apparent":
        return apparent_film(grease, speed, film, shear_rate)
    eta = grease.viscosity(reading, base_oil_viscosity=base_oil_viscosity)
    return GreaseFilm(film(eta), eta, None, 0)
