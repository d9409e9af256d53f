r"""Traction laws of a rolling contact, written once for films and dynamics.

Closed-form traction curve (cage-less ball bearing, paper B)
------------------------------------------------------------
``mu = mu_lim tanh(|v_s| / max(s0 |u_e|, v_reg))``: a traction curve over the slide-to-roll ratio
SRR = |v_s|/u_e (initial slope mu_lim/s0, limiting value mu_lim, the shape of Newtonian-then-
limiting-shear EHL traction curves, e.g. Johnson & Tevaarwerk 1977, Proc. R. Soc. A 356, 215),
regularised at vanishing entrainment by the sliding speed v_reg (then a smoothed Coulomb law).

Grease traction of paper A (Wu, Xu & Deng 2018)
-----------------------------------------------
Sign convention: ``slip_speed`` is the surface speed of the *other* body minus that of the body the
force acts on; the force drags the body along it (odd in slip).

``"paper"``: eqs. 12-13 exactly as written (linear in sliding speed, phi0 at atmospheric pressure, no
yield stress, no limit), per unit length of contact (eq. 12's force of a slice is this
times l_e/n_s)::

    f' = pi eps eta R'^(1/2) (v_b - v_r) / (2^(1/2) h0^(1/2))                         (eq. 12)
    eps = (2/pi) [atan z - z/(1 + z^2)],   z = 2^(1/2) b / (R' h0)^(1/2)             (eq. 13)

eta is phi0 in the paper (its number read as Pa s); :class:`lubedyn.lubrication.laws.grease.Grease.viscosity`
gives it under each reading.  Rebuilt from the garbled text: eq. 12 prints ``(3 v_b - v_r(`` and
``(3 v_r - v_b(``; read here as (v_b - v_r) and (v_r - v_b), the "3" and "(" being extraction debris
of the large brackets (as elsewhere in that text), which makes f_b = -f_r and the law linear in the
sliding speed.  (The literal 3 v_b - v_r would be a Couette-plus-Poiseuille mix
with a traction at zero slip.)  What eq. 12 integrates (shown by quadrature in the tests): with
c = (R' h0/2)^(1/2), z = b/c and the gap h(x) = h0 (1 + x^2/c^2) = h0 + 2 x^2/R'::

    f' = eta (v_b - v_r) int_{-b}^{b} 2 (h - h0)/h^2 dx  ->  eta (v_b - v_r) int dx/h   (b >> c)

i.e. the Couette traction of that gap for a wide strip.  Note the paper's gap is 2x^2/R', four times a
cylinder's x^2/(2R'): kept as printed.

``"limited"`` (an extension, not the paper): Herschel-Bulkley with Barus consistency (eq. 26's law) and
a limiting shear stress in Bair & Winer's (1979, J. Lubr. Technol. 101, 258) form, integrated over the
Hertz pressure with a uniform film h (shear rate D = slip/h)::

    tau_HB = tau_y r(D) + phi0 exp(alpha p) |D|^n            (r: Papanastasiou, see grease.py)
    tau    = sign(D) tau_L (1 - exp(-tau_HB/tau_L)),   tau_L = tau_L0 + gamma_L p

so tau -> tau_HB when tau_HB << tau_L, and |tau| < tau_L: the mean traction coefficient over a Hertz
contact stays below gamma_L + tau_L0 A/W.  tau_L0 = inf gives eq. 26 unbounded, as printed.

- line strip [-b, b], p = p0 (1 - x^2/b^2)^(1/2): with x = b cos(theta),
  f' = 2 b int_0^(pi/2) tau(p0 sin theta) sin theta d theta                         (per unit length)
- Hertz ellipse (semi-axes a, b), p = p0 (1 - r^2)^(1/2): with s = (1 - r^2)^(1/2),
  f = 2 pi a b int_0^1 tau(p0 s) s ds                                               (eq. 27, f = int tau dA)

both by a fixed :data:`N_GAUSS`-point Gauss-Legendre rule (smooth integrands after the substitutions;
exact to round-off in the Newtonian and Barus limits; with the limit switching on inside the contact,
measured against adaptive quadrature: strip within 3e-4, ellipse within 2e-6, in
tests/test_laws_traction_paper_a.py).  With Barus at paper A's pressures (alpha p0 = 20-30) the
limited law is a near-Coulomb curve: at the cone contact (p0 0.66 GPa, h 5 um, polyurea, tau_L0 1 MPa,
gamma_L 0.07) the mean traction coefficient is 0.061 at 1 nm/s of sliding, 0.067 at 1 um/s, 0.071 at
1 cm/s (measured): its initial slope is infinite.  The film's shear elasticity gives it a finite one
(Johnson & Tevaarwerk 1977: a Maxwell fluid, elastic at small strain): :func:`elastic_strip_slope` is the
elastic limit's slope 2 G b^2/(u_e h) per metre of strip (G the film's shear modulus) and
:func:`elastic_limited` joins the two in series, F = F_v tanh(k v_s/F_v).  Without it the tapered
bearing's rollers are held by a near-Coulomb law whose stiffness no explicit integrator can follow
(measured: 2 ms of paper A's bearing did not finish in 4 minutes with DOPRI5 at rtol 1e-7).  The grease
parameters travel as one tuple ``rheology = (tau_y, phi0, n, alpha, tau_L0, gamma_L, D_r)``
(:func:`rheology`).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from .jit import INLINE

RACEWAY_LAWS = ("paper", "limited")
N_GAUSS = 32
_X, _W = np.polynomial.legendre.leggauss(N_GAUSS)
_S_NODES, _S_WEIGHTS = 0.5 * (_X + 1.0), 0.5 * _W                       # on [0, 1]
_T_NODES, _T_WEIGHTS = 0.25 * math.pi * (_X + 1.0), 0.25 * math.pi * _W   # on [0, pi/2]
_SIN_T = np.sin(_T_NODES)


@njit(**INLINE)  # small leaf of the bearing rhs (see lubedyn.dynamics.cageless)
def traction_coefficient(slip_speed, entrainment_speed, mu_lim, srr_ref, v_reg):
    """``mu_lim tanh(|v_s| / max(srr_ref |u_e|, v_reg))`` (>= 0)."""
    scale = srr_ref * abs(entrainment_speed)
    if scale < v_reg:
        scale = v_reg
    return mu_lim * math.tanh(abs(slip_speed) / scale)


# ---------------------------------------------------------------- paper A, eqs. 12-13


@njit(**INLINE)
def paper_epsilon(half_width, radius, film):
    """eps of eq. 13: (2/pi) [atan z - z/(1 + z^2)], z = 2^(1/2) b/(R' h0)^(1/2) (series below z = 1e-2)."""
    z = math.sqrt(2.0) * half_width / math.sqrt(radius * film)
    if z < 1e-2:
        z2 = z * z
        return 2.0 / math.pi * z * z2 * (2.0 / 3.0 - z2 * (0.8 - z2 * 6.0 / 7.0))
    return 2.0 / math.pi * (math.atan(z) - z / (1.0 + z * z))


@njit(**INLINE)
def paper_raceway_traction(slip_speed, viscosity, radius, film, half_width):
    """Eq. 12 per unit length [N/m]: pi eps eta R'^(1/2) v_s / (2^(1/2) h0^(1/2)) (linear, unlimited)."""
    eps = paper_epsilon(half_width, radius, film)
    return math.pi * eps * viscosity * math.sqrt(radius / (2.0 * film)) * slip_speed


# ---------------------------------------------------------------- limited Herschel-Bulkley (extension)


def rheology(grease, limiting_stress=math.inf, limiting_slope=0.0, yield_rate=0.0):
    """The tuple (tau_y, phi0, n, alpha, tau_L0, gamma_L, D_r) the limited leaves take, from a
    :class:`lubedyn.lubrication.laws.grease.Grease`; ``limiting_stress`` tau_L0 [Pa] (inf: no limit),
    ``limiting_slope`` gamma_L = d tau_L/dp, ``yield_rate`` D_r [1/s]."""
    return (float(grease.yield_stress), float(grease.consistency), float(grease.exponent),
            float(grease.pressure_viscosity), float(limiting_stress), float(limiting_slope), float(yield_rate))


@njit(**INLINE)
def _rate_terms(shear_rate, rheo):
    """(tau_y r(D), |D|^n): the parts of the Herschel-Bulkley stress that do not depend on pressure, so a
    quadrature over a contact at one shear rate computes them once (:func:`lubedyn.lubrication.laws.grease.hb_stress`'s
    terms)."""
    tau_y, phi0, n, alpha, tau_l0, gamma_l, d_r = rheo
    d = abs(shear_rate)
    if d == 0.0:
        return 0.0, 0.0
    ty = tau_y if d_r <= 0.0 else tau_y * -math.expm1(-d / d_r)
    return ty, d**n


@njit(**INLINE)
def _limited_magnitude(ty, dn, pressure, rheo):
    """|tau| [Pa] of the limited law from :func:`_rate_terms` at gauge pressure p."""
    tau_y, phi0, n, alpha, tau_l0, gamma_l, d_r = rheo
    p = max(pressure, 0.0)
    tau = ty + phi0 * math.exp(alpha * p) * dn
    tau_l = tau_l0 + gamma_l * p
    if tau_l < math.inf and tau > 0.0:
        tau = tau_l * -math.expm1(-tau / tau_l)
    return tau


@njit(**INLINE)
def limited_stress(shear_rate, pressure, rheo):
    """tau [Pa] of the limited law at shear rate D and gauge pressure p (sign of D)."""
    ty, dn = _rate_terms(shear_rate, rheo)
    tau = _limited_magnitude(ty, dn, pressure, rheo)
    return tau if shear_rate >= 0.0 else -tau


@njit(**INLINE)
def limited_strip_traction(slip_speed, film, half_width, peak_pressure, rheo):
    """Traction per unit length [N/m] of a Hertz line strip (half-width b, peak p0) sheared at
    D = slip/h: 2 b int_0^(pi/2) tau(p0 sin t) sin t dt (Gauss-Legendre; the shear-rate terms once)."""
    ty, dn = _rate_terms(slip_speed / film, rheo)
    total = 0.0
    for i in range(_T_NODES.size):
        total += _T_WEIGHTS[i] * _SIN_T[i] * _limited_magnitude(ty, dn, peak_pressure * _SIN_T[i], rheo)
    return 2.0 * half_width * (total if slip_speed >= 0.0 else -total)


@njit(**INLINE)
def elastic_strip_slope(shear_modulus, half_width, entrainment_speed, film):
    """Initial slope [N s/m per metre of contact] of a line strip's traction against its sliding speed when
    the film shears elastically (Johnson & Tevaarwerk 1977, Proc. R. Soc. A 356, 215: the Maxwell
    fluid's elastic limit): an element entering at x = -b has been strained by v_s (x + b)/(u_e h) when it
    reaches x, so tau = G v_s (x + b)/(u_e h) and the strip's traction per length is
    int_{-b}^{b} tau dx = 2 G b^2 v_s/(u_e h).  inf when G = inf (no compliance)."""
    if not math.isfinite(shear_modulus):
        return math.inf
    return 2.0 * shear_modulus * half_width * half_width / (max(entrainment_speed, 1e-12) * film)


@njit(**INLINE)
def elastic_limited(force, slope, slip_speed):
    """The traction of a viscous (or limited) law ``force`` [N] (>= 0, at |v_s| = ``slip_speed``) in
    series with an elastic film of initial ``slope`` k [N s/m]: F = F_v tanh(k |v_s| / F_v).  F -> k |v_s|
    where the elastic strain limits it (small slip: a finite initial slope, the near-Coulomb Barus law's
    infinite one removed) and -> F_v where the fluid yields; k = inf returns F_v.  A smooth series
    combination (the exact Maxwell steady state needs an ODE through the contact), so between the two
    limits it is within the tanh's shape of it, not exact."""
    if force <= 0.0:
        return 0.0
    if not slope < math.inf:
        return force
    return force * math.tanh(slope * slip_speed / force)


@njit(**INLINE)
def limited_ellipse_traction(slip_speed, film, semi_a, semi_b, peak_pressure, rheo):
    """Traction [N] of a Hertz ellipse (semi-axes a, b, peak p0) sheared at D = slip/h:
    2 pi a b int_0^1 tau(p0 s) s ds (Gauss-Legendre; eq. 27 with f = int tau dA)."""
    ty, dn = _rate_terms(slip_speed / film, rheo)
    total = 0.0
    for i in range(_S_NODES.size):
        total += _S_WEIGHTS[i] * _S_NODES[i] * _limited_magnitude(ty, dn, peak_pressure * _S_NODES[i], rheo)
    return 2.0 * math.pi * semi_a * semi_b * (total if slip_speed >= 0.0 else -total)
