r"""Slice law of a roller/raceway line contact (paper A, Wu, Xu & Deng 2018, eqs. 1-11).

Whole-roller line law (Palmgren, *Ball and Roller Bearing Engineering*, 3rd ed. 1959; Harris &
Kotzalas, *Essential Concepts of Bearing Technology*, 5th ed. 2007, eq. 6.41), one roller/raceway
contact of effective length l::

    delta = 3.84e-5 Q^0.9 / l^0.8          [delta, l in mm, Q in N]
    <=>  Q = K_L delta^(10/9),  K_L = (3.84e-5)^(-10/9) l^(8/9) = 80,593 l^(8/9)   [N, mm]
                                K_L = 8.059e10 l^(8/9)                             [SI]

Paper A writes the same law per slice with the equivalent modulus (its eq. 11, ref. [13])::

    k_w = 0.356 E' l_e^(8/9) / n_s,   K_L = n_s k_w = 0.356 E' l_e^(8/9)

and E' = 1e6 (3.84e-5)^(-10/9) / 0.356 = 2.264e11 Pa reproduces Palmgren exactly
(:func:`palmgren_modulus`): E' = E/(1 - nu^2) of two equal bodies, i.e. steel with E = 206 GPa,
nu = 0.3 (paper A's 205 GPa, 0.3 gives E' = 225.3 GPa: K_L 0.49 % below Palmgren's).  ISO/TS
16281 (2008) writes the roller's two contacts in series as Q = 35,948 l^(8/9) delta_total^(10/9)
[N, mm]; Palmgren's two equal contacts in series give 80,593/2^(10/9) = 37,310, 3.8 % stiffer
(3.4 % less approach at equal load).

Slices (eq. 11): n_s slices of width l_e/n_s, slice k carries

    q_k = k_w delta_k^(10/9) (1 + 1.5 alpha_e d(delta_k)/dt),   k_w = K_L / n_s,   q_k >= 0

(eq. 11 prints c_w = 1.5 alpha_e k_w delta^(10/9) multiplying the approach speed: a Hunt-Crossley
form, alpha_e = 0.08-0.32 s/m for steel [ref. 14 of the paper]).  Because the slice law has the
exponent of the whole-roller law and k_w = K_L/n_s, n_s slices at one interference sum exactly to
K_L delta^(10/9) for every n_s (Hertz's line law is not additive along the line in general: the
slice law is the usual "independent slices" approximation of ISO/TS 16281 and Harris).

Slice interference (eqs. 1-7, rebuilt: the printed eqs. 5-7 lost their indices).  In the meridional
plane (x axial, r radial) of a roller without skew, slice k is a disc of radius rho_k (crown
included) centred at S_k on the roller axis of unit direction e.  A raceway is the straight line
through X with unit normal n pointing from the raceway towards the roller.  The disc's rim point
nearest the line is S_k - rho_k (n - (n.e) e)/|n - (n.e) e|, so the interference (positive = overlap)
measured along n is

    delta_k = rho_k sqrt(1 - (n.e)^2) - n.(S_k - X)

which is eq. 7's (r_ba3 - xi) cos(alpha_p) for a roller with the race's contact angle, and keeps
the roller's tilt (through e) and its taper (through rho_k).  Plain floats; :func:`slice_force` and
:func:`slice_interference` are numba ``INLINE`` leaves for the compiled right-hand sides.

In three dimensions (a skewed roller, :func:`slice_contact_3d`): a raceway is a cone about the bearing
axis x, and the point of a surface of revolution nearest any point lies in that point's meridional
plane, so the same formula holds with the 3-D normal n3 = n_x e_x + n_r e_r(S), e_r(S) the radial unit
vector through the slice centre, and the meridional coordinates (S_x, |S_yz|) of S:

    delta = rho sqrt(1 - (n3.e)^2) - [n_x (S_x - X_x) + n_r (|S_yz| - X_r)]

at the rim point P = S - rho (n3 - (n3.e) e)/|n3 - (n3.e) e|.  The one approximation: the rim point
is not in S's meridional plane when the roller is skewed, where the raceway's circumferential curvature
enters; against the exact distance over the rim (tests/test_trb_geometry.py) the interference is within
3e-17 m unskewed and 1.2e-12 m at a skew of 2e-3 rad for paper A's roller, the contact point within
5.4e-8 m.
"""
from __future__ import annotations

import math

from numba import njit

from ..errors import InputError
from .contact import positive
from .jit import INLINE

PALMGREN = 3.84e-5          # delta [mm] = 3.84e-5 Q^0.9 / l^0.8 (Palmgren 1959)
PAPER_A_LINE_FACTOR = 0.356  # k_w = 0.356 E' l^(8/9) / n_s (paper A eq. 11, its ref. [13])
LINE_EXPONENT = 10.0 / 9.0


def palmgren_line_constant(length: float) -> float:
    """K_L [N/m^(10/9)] of Q = K_L delta^(10/9) for one roller/raceway contact of effective
    ``length`` [m] (Palmgren: K_L = (3.84e-5)^(-10/9) l^(8/9) in N, mm; times 1e6 for SI)."""
    length = positive("effective length [m]", length)
    return 1e6 * PALMGREN ** (-LINE_EXPONENT) * length ** (8.0 / 9.0)


def line_constant(length: float, e_prime: float) -> float:
    """K_L = 0.356 E' l^(8/9) [N/m^(10/9)] (paper A eq. 11 times n_s)."""
    return PAPER_A_LINE_FACTOR * positive("equivalent modulus E' [Pa]", e_prime) * \
        positive("effective length [m]", length) ** (8.0 / 9.0)


def palmgren_modulus() -> float:
    """E' [Pa] with which 0.356 E' l^(8/9) equals Palmgren's constant (2.27e11 Pa)."""
    return 1e6 * PALMGREN ** (-LINE_EXPONENT) / PAPER_A_LINE_FACTOR


def slice_constant(line_const: float, n_slices: int) -> float:
    """k_w = K_L / n_s [N/m^(10/9)]: n_s equal slices at one interference sum to K_L delta^(10/9)."""
    if int(n_slices) != n_slices or n_slices < 1:
        raise InputError(f"n_slices = {n_slices!r} must be an integer >= 1")
    return positive("line constant K_L [N/m^(10/9)]", line_const) / int(n_slices)


def approach(load: float, line_const: float) -> float:
    """delta [m] of Q = K_L delta^(10/9) for ``load`` [N] (inverse of the line law)."""
    if load <= 0.0:
        return 0.0
    return (load / line_const) ** 0.9


def slice_energy(delta: float, k_w: float) -> float:
    """Stored energy k_w delta^(19/9) 9/19 [J] of one slice (0 without contact): d/d(delta) = q."""
    return k_w * delta ** (19.0 / 9.0) * (9.0 / 19.0) if delta > 0.0 else 0.0


@njit(**INLINE)
def slice_force(delta, delta_dot, k_w, alpha_e):
    """Eq. 11: q = k_w delta^(10/9) (1 + 1.5 alpha_e delta_dot), >= 0; 0 for delta <= 0."""
    if delta <= 0.0:
        return 0.0
    q = k_w * delta ** (10.0 / 9.0) * (1.0 + 1.5 * alpha_e * delta_dot)
    return q if q > 0.0 else 0.0


@njit(**INLINE)
def slice_interference(sx, sr, ex, er, rho, px, pr, nx, nr):
    """delta = rho sqrt(1 - (n.e)^2) - n.(S - X) [m] of a slice disc (centre S, axis e, radius rho)
    against a raceway line through X with unit normal n towards the roller (meridional plane)."""
    c = nx * ex + nr * er
    return rho * math.sqrt(max(1.0 - c * c, 0.0)) - (nx * (sx - px) + nr * (sr - pr))


@njit(**INLINE)
def slice_contact_3d(s0, s1, s2, e0, e1, e2, rho, px, pr, nx, nr):
    """``(delta, P_x, P_y, P_z, n_x, n_y, n_z)``: the interference [m] of a slice disc (centre S, unit axis
    e, radius rho; inertial frame, bearing axis x) with a conical raceway given in the meridional plane
    by a point (px, pr) and the unit normal (nx, nr) towards the roller, the rim point P nearest the
    raceway, and the raceway's unit normal n3 at P (towards the roller: the raceway pushes the slice
    along +n3).  Module docstring, "In three dimensions"."""
    r = math.sqrt(s1 * s1 + s2 * s2)
    ey, ez = s1 / r, s2 / r
    n0, n1, n2 = nx, nr * ey, nr * ez
    c = n0 * e0 + n1 * e1 + n2 * e2
    m0, m1, m2 = n0 - c * e0, n1 - c * e1, n2 - c * e2
    sq = math.sqrt(max(1.0 - c * c, 1e-300))
    delta = rho * sq - (nx * (s0 - px) + nr * (r - pr))
    k = rho / sq
    return delta, s0 - k * m0, s1 - k * m1, s2 - k * m2, n0, n1, n2


@njit(**INLINE)
def slice_interference_gradient(ex, er, rho, u, nx, nr):
    """(d delta/d S_x, d delta/d S_r, d delta/d beta) of :func:`slice_interference` for a slice at
    ``u`` along the axis e = (cos beta, sin beta) from the roller's reference point C (S = C + u e)."""
    c = nx * ex + nr * er
    dc = -nx * er + nr * ex          # n.(de/dbeta)
    s = math.sqrt(max(1.0 - c * c, 1e-300))
    return -nx, -nr, -rho * c * dc / s - u * dc


@njit(**INLINE)
def slice_interference_curvature(ex, er, rho, u, nx, nr):
    """d^2 delta / d beta^2 of :func:`slice_interference` (the only second derivative: delta is
    linear in S and X): -rho [(c'^2 - c^2)/s + c^2 c'^2/s^3] + u c, c = n.e, c' = n.de/dbeta,
    s = sqrt(1 - c^2)."""
    c = nx * ex + nr * er
    dc = -nx * er + nr * ex
    s = math.sqrt(max(1.0 - c * c, 1e-300))
    return -rho * ((dc * dc - c * c) / s + c * c * dc * dc / (s * s * s)) + u * c
