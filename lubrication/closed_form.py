r"""Closed-form and semi-analytic film results, used to verify the Reynolds solver.

Every function is independent of :mod:`lubedyn.lubrication.reynolds` (no finite
elements): closed forms from the literature, or one-dimensional integrals and
ODEs evaluated with scipy to an accuracy far below the solver's discretisation
error.  SI units throughout; loads of 1-D (infinitely wide/long) films are per
unit width [N/m].

Velocity conventions
--------------------
The Reynolds equation is written with the *mean* surface velocity
u_m = (U_lower + U_upper)/2 (see :mod:`lubedyn.lubrication.reynolds`)::

    d/dx (h^3/(12 eta) dp/dx) = u_m dh/dx + dh/dt.

- slider, step, cylinder and pocket functions take ``mean_speed`` = u_m (a
  slider whose runner moves at U over a fixed pad has u_m = U/2);
- journal-bearing functions take ``surface_speed`` U = omega R, the journal's
  surface speed with the bearing fixed (u_m = U/2), as in the classical texts.

Journal frames
--------------
Long and short journal results are stated in the eccentricity frame: the
journal centre is displaced by e = eps c, the gap is h = c (1 + eps cos phi)
with phi measured from the *largest* gap in the direction of rotation.
``W_r`` is the film force component that opposes the displacement, ``W_t`` the
component along the displacement direction turned by +90 deg in the direction
of rotation.  :func:`short_journal_forces` works in the solver's fixed frame
instead (see :class:`lubedyn.lubrication.gaps.JournalBearing`).

References
----------
- B. J. Hamrock, S. R. Schmid, B. O. Jacobson, *Fundamentals of Fluid Film
  Lubrication*, 2nd ed., Marcel Dekker 2004 (ch. 8 slider, 10 journals,
  12 squeeze films, 17 Martin).
- O. Pinkus, B. Sternlicht, *Theory of Hydrodynamic Lubrication*, McGraw-Hill
  1961 (finite slider by Fourier series).
- M. I. Friswell, J. E. T. Penny, S. D. Garvey, A. W. Lees, *Dynamics of
  Rotating Machines*, CUP 2010, sec. 5.5 (short-bearing coefficients).
- D. W. Childs, *Turbomachinery Rotordynamics*, Wiley 1993, ch. 3.
- H. M. Martin, Lubrication of gear teeth, *Engineering* 102 (1916) 119.
- M. Fowell, A. V. Olver, A. D. Gosman, H. A. Spikes, I. Pegg, Entrainment
  and inlet suction: two mechanisms of hydrodynamic lubrication in textured
  bearings, *J. Tribol.* 129 (2007) 336 (pocketed slider, JFO).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from scipy import integrate, optimize

__all__ = [
    "inclined_slider_pressure", "inclined_slider_load", "inclined_slider_max_pressure_position",
    "inclined_slider_optimum_ratio", "rayleigh_step_pressure", "rayleigh_step_load",
    "long_journal_sommerfeld_pressure", "long_journal_sommerfeld_load",
    "long_journal_half_sommerfeld_load", "long_journal_reynolds", "short_journal_load",
    "short_journal_forces", "short_journal_coefficients", "parallel_disk_squeeze_force",
    "sphere_plane_squeeze_force", "martin_rigid_cylinder", "finite_slider_load",
    "jfo_slider", "JFOSlider",
]


# --------------------------------------------------------------------------
# inclined and step sliders (infinitely wide)


def _slider_ratio(h_in, h_out):
    return h_in / h_out - 1.0


def inclined_slider_pressure(x, h_in, h_out, length, eta, mean_speed):
    r"""Pressure [Pa] of the infinitely wide plane inclined slider.

    h = h_in + (h_out - h_in) x / length, p = 0 at x = 0 and x = length::

        p = 12 eta u_m length K X (1 - X) / (h_out^2 (2 + K) (1 + K - K X)^2)

    with X = x/length, K = h_in/h_out - 1 (Hamrock et al. 2004, eq. 8.38 with
    their u_b = 2 u_m).  ``mean_speed`` u_m = (U_lower + U_upper)/2 [m/s],
    positive from inlet (x = 0) to outlet.

    >>> round(float(inclined_slider_pressure(2/3, 2.0, 1.0, 1.0, 1.0, 1.0)), 6)
    0.5
    """
    K = _slider_ratio(h_in, h_out)
    X = np.asarray(x, dtype=float) / length
    return 12.0 * eta * mean_speed * length * K * X * (1.0 - X) / (h_out**2 * (2.0 + K) * (1.0 + K - K * X) ** 2)


def inclined_slider_load(h_in, h_out, length, eta, mean_speed):
    r"""Load per unit width [N/m] of the infinitely wide inclined slider::

        W = 12 eta u_m length^2 / (K^2 h_out^2) [ln(1 + K) - 2 K / (2 + K)]

    (Hamrock et al. 2004, eq. 8.45 with u_b = 2 u_m); u_m the mean speed.
    """
    K = _slider_ratio(h_in, h_out)
    return 12.0 * eta * mean_speed * length**2 / (K**2 * h_out**2) * (np.log1p(K) - 2.0 * K / (2.0 + K))


def inclined_slider_max_pressure_position(h_in, h_out, length):
    """Position [m] of the pressure maximum, x_m = length (1 + K)/(2 + K)."""
    K = _slider_ratio(h_in, h_out)
    return length * (1.0 + K) / (2.0 + K)


def inclined_slider_optimum_ratio() -> float:
    """K = h_in/h_out - 1 that maximises the load at fixed h_out (about 1.189).

    Root of d/dK [(ln(1 + K) - 2K/(2 + K)) / K^2] (Hamrock et al. 2004, sec. 8.6.2).
    """
    def dfdk(K):
        f = np.log1p(K) - 2.0 * K / (2.0 + K)
        df = 1.0 / (1.0 + K) - 4.0 / (2.0 + K) ** 2
        return df / K**2 - 2.0 * f / K**3

    return float(optimize.brentq(dfdk, 0.5, 3.0, xtol=1e-14))


def rayleigh_step_pressure(h_in, h_out, length_in, length_out, eta, mean_speed):
    r"""Pressure [Pa] at the step of the infinitely wide Rayleigh step slider.

    Inlet land of gap h_in and length ``length_in``, then outlet land h_out,
    ``length_out``; p = 0 at both ends; flux continuity at the step gives::

        p_s = 12 eta u_m (h_in - h_out) / (h_in^3/length_in + h_out^3/length_out)

    (Hamrock et al. 2004, sec. 8.8); u_m the mean speed.  The pressure is
    linear on each land.
    """
    return 12.0 * eta * mean_speed * (h_in - h_out) / (h_in**3 / length_in + h_out**3 / length_out)


def rayleigh_step_load(h_in, h_out, length_in, length_out, eta, mean_speed):
    """Load per unit width [N/m] of the Rayleigh step: p_s (length_in + length_out)/2."""
    p_s = rayleigh_step_pressure(h_in, h_out, length_in, length_out, eta, mean_speed)
    return 0.5 * p_s * (length_in + length_out)


# --------------------------------------------------------------------------
# infinitely long journal bearing


def long_journal_sommerfeld_pressure(phi, radius, clearance, eccentricity_ratio, eta, surface_speed):
    r"""Full-Sommerfeld pressure [Pa] of the infinitely long journal bearing.

    h = c (1 + eps cos phi), phi from the largest gap in the direction of
    rotation, p(phi = 0) = 0::

        p = 6 eta U R eps sin(phi) (2 + eps cos phi) / (c^2 (2 + eps^2) (1 + eps cos phi)^2)

    ``surface_speed`` U = omega R (journal; bearing fixed, u_m = U/2).
    Hamrock et al. 2004, eq. 10.26.
    """
    phi = np.asarray(phi, dtype=float)
    e, c = eccentricity_ratio, clearance
    return (6.0 * eta * surface_speed * radius * e * np.sin(phi) * (2.0 + e * np.cos(phi))
            / (c**2 * (2.0 + e**2) * (1.0 + e * np.cos(phi)) ** 2))


def long_journal_sommerfeld_load(radius, clearance, eccentricity_ratio, eta, surface_speed):
    r"""Full-Sommerfeld load per unit length [N/m], attitude angle 90 deg::

        W = 12 pi eta U R^2 eps / (c^2 (2 + eps^2) sqrt(1 - eps^2))

    (Hamrock et al. 2004, eq. 10.36); U = omega R the journal surface speed.
    The force is W_t only (W_r = 0).
    """
    e = eccentricity_ratio
    return 12.0 * np.pi * eta * surface_speed * radius**2 * e / (clearance**2 * (2.0 + e**2) * np.sqrt(1.0 - e**2))


def long_journal_half_sommerfeld_load(radius, clearance, eccentricity_ratio, eta, surface_speed):
    r"""Half-Sommerfeld (Guembel) force components per unit length [N/m].

    The Sommerfeld pressure kept on 0 < phi < pi only::

        W_r = 12 eta U R^2 eps^2 / (c^2 (2 + eps^2) (1 - eps^2))
        W_t = 6 pi eta U R^2 eps / (c^2 (2 + eps^2) sqrt(1 - eps^2))

    (Hamrock et al. 2004, eqs. 10.44-10.45; Childs 1993, sec. 3.4).  Returns
    ``(W_r, W_t)``; U = omega R the journal surface speed.
    """
    e, c, R = eccentricity_ratio, clearance, radius
    base = eta * surface_speed * R**2 / (c**2 * (2.0 + e**2))
    return 12.0 * base * e**2 / (1.0 - e**2), 6.0 * np.pi * base * e / np.sqrt(1.0 - e**2)


@dataclass(frozen=True)
class LongJournalReynolds:
    """Swift-Stieber (Reynolds-condition) long journal, see :func:`long_journal_reynolds`."""

    phi_cavitation: float  # film end [rad], p = dp/dphi = 0
    W_r: float  # [N/m], opposing the displacement
    W_t: float  # [N/m], displacement turned +90 deg in the direction of rotation
    pressure_scale: float  # 6 eta U R / c^2 [Pa]
    eccentricity_ratio: float

    def pressure(self, phi):
        """Pressure [Pa] at phi in [0, 2 pi) (zero beyond the film end)."""
        phi = np.atleast_1d(np.asarray(phi, dtype=float)) % (2.0 * np.pi)
        out = np.zeros_like(phi)
        for i, f in enumerate(phi):
            if f < self.phi_cavitation:
                out[i] = self.pressure_scale * integrate.quad(self._dp, 0.0, f, epsabs=1e-12, epsrel=1e-12)[0]
        return out

    def _dp(self, phi):
        e = self.eccentricity_ratio
        H = 1.0 + e * np.cos(phi)
        Hc = 1.0 + e * np.cos(self.phi_cavitation)
        return 1.0 / H**2 - Hc / H**3


def long_journal_reynolds(radius, clearance, eccentricity_ratio, eta, surface_speed) -> LongJournalReynolds:
    r"""Infinitely long journal with Swift-Stieber (Reynolds) conditions, semi-analytic.

    The film starts at the largest gap (phi = 0, p = 0) and ends at phi_c
    where p = dp/dphi = 0 (Hamrock et al. 2004, sec. 10.4.3)::

        p(phi) = 6 eta U R / c^2  int_0^phi (1/H^2 - H_c/H^3) dphi',  H = 1 + eps cos phi

    phi_c solves p(phi_c) = 0 on (pi, 2 pi) (brentq); the force components
    are quadratures of p.  U = omega R the journal surface speed.
    """
    e = eccentricity_ratio
    scale = 6.0 * eta * surface_speed * radius / clearance**2

    def end_condition(phic):
        Hc = 1.0 + e * np.cos(phic)
        f = lambda t: 1.0 / (1.0 + e * np.cos(t)) ** 2 - Hc / (1.0 + e * np.cos(t)) ** 3
        return integrate.quad(f, 0.0, phic, epsabs=1e-13, epsrel=1e-12, limit=200)[0]

    phic = optimize.brentq(end_condition, np.pi + 1e-9, 2.0 * np.pi - 1e-9, xtol=1e-14)
    sol = LongJournalReynolds(phic, 0.0, 0.0, scale, e)
    p = lambda t: sol.pressure(t)[0]
    # force on the journal per unit length: int p (d cos(phi) + n sin(phi)) R dphi, d the
    # displacement direction, n = d turned +90 deg in the direction of rotation
    fd = integrate.quad(lambda t: p(t) * np.cos(t), 0.0, phic, epsabs=0, epsrel=1e-10, limit=200)[0]
    fn = integrate.quad(lambda t: p(t) * np.sin(t), 0.0, phic, epsabs=0, epsrel=1e-10, limit=200)[0]
    return LongJournalReynolds(phic, -fd * radius, fn * radius, scale, e)


# --------------------------------------------------------------------------
# short journal bearing (Ocvirk)


def short_journal_load(radius, clearance, length, eccentricity_ratio, eta, surface_speed):
    r"""Short-bearing (Ocvirk, half-Sommerfeld) static force [N] and attitude angle [rad].

    ::

        W_r = eta U L^3 eps^2 / (c^2 (1 - eps^2)^2)
        W_t = pi eta U L^3 eps / (4 c^2 (1 - eps^2)^(3/2))
        W = eta U L^3 eps / (4 c^2 (1 - eps^2)^2) sqrt(16 eps^2 + pi^2 (1 - eps^2))
        tan(attitude) = W_t / W_r = pi sqrt(1 - eps^2) / (4 eps)

    (Hamrock et al. 2004, sec. 10.6; Childs 1993, eq. 3.29); U = omega R the
    journal surface speed, L the bearing length.  ``radius`` is not needed by
    the short-bearing theory and is accepted for a uniform signature.
    Returns ``(W, attitude, W_r, W_t)``.
    """
    e, c = eccentricity_ratio, clearance
    W_r = eta * surface_speed * length**3 * e**2 / (c**2 * (1.0 - e**2) ** 2)
    W_t = np.pi * eta * surface_speed * length**3 * e / (4.0 * c**2 * (1.0 - e**2) ** 1.5)
    return float(np.hypot(W_r, W_t)), float(np.arctan2(W_t, W_r)), float(W_r), float(W_t)


def short_journal_forces(radius, clearance, length, eta, surface_speed, e_x, e_y, v_x=0.0, v_y=0.0):
    r"""Half-Sommerfeld short-bearing force [N] on the journal in the solver's fixed frame.

    Frame of :class:`lubedyn.lubrication.gaps.JournalBearing`: theta from +x towards
    +y, the journal turning in +theta with surface speed U = omega R
    (u_m = U/2), h = c - e_x cos(theta) - e_y sin(theta), centre velocity
    (v_x, v_y) so that dh/dt = -v_x cos(theta) - v_y sin(theta).  The short
    bearing pressure (axial coordinate z in [-L/2, L/2])::

        p = 6 eta (u_m dh/(R dtheta) + dh/dt) (z^2 - L^2/4) / h^3,

    integrated over z, is P(theta) = -eta L^3 g(theta)/h^3 with
    g = u_m dh/(R dtheta) + dh/dt = A sin(theta) + B cos(theta); the
    half-Sommerfeld film keeps P > 0, i.e. the half circle where g < 0, and
    F = int P (-cos theta, -sin theta) R dtheta over it by scipy quad.
    Returns ``np.array([F_x, F_y])``; finite differences of it give K and C.
    """
    R, L = radius, length
    um = 0.5 * surface_speed
    A = um * e_x / R - v_y
    B = -um * e_y / R - v_x
    if A == 0.0 and B == 0.0:
        return np.zeros(2)
    beta = np.arctan2(B, A)  # g = M sin(theta + beta)
    t0, t1 = np.pi - beta, 2.0 * np.pi - beta

    def P(t):
        h = clearance - e_x * np.cos(t) - e_y * np.sin(t)
        return -eta * L**3 * (A * np.sin(t) + B * np.cos(t)) / h**3

    kw = dict(epsabs=0.0, epsrel=1e-12, limit=200)
    fx = integrate.quad(lambda t: -P(t) * np.cos(t), t0, t1, **kw)[0] * R
    fy = integrate.quad(lambda t: -P(t) * np.sin(t), t0, t1, **kw)[0] * R
    return np.array([fx, fy])


def short_journal_coefficients(radius, clearance, length, eccentricity_ratio, eta, surface_speed):
    r"""Short-bearing (half-Sommerfeld) stiffness [N/m] and damping [N s/m] matrices.

    Friswell et al. (2010), eqs. 5.77-5.78 (also ROSS
    ``calculate_analytical_*_matrix``), in their load frame: with f0 the
    static load (:func:`short_journal_load`),
    h0 = 1/(pi^2 (1 - eps^2) + 16 eps^2)^(3/2), omega = U/R::

        K = f0/c [[a_uu, a_uv], [a_vu, a_vv]],  C = f0/(c omega) [[b_uu, b_uv], [b_vu, b_vv]]
        a_uu = 4 h0 (pi^2 (2 - eps^2) + 16 eps^2)
        a_uv = h0 pi (pi^2 (1 - eps^2)^2 - 16 eps^4) / (eps sqrt(1 - eps^2))
        a_vu = -h0 pi (pi^2 (1 - eps^2)(1 + 2 eps^2) + 32 eps^2 (1 + eps^2)) / (eps sqrt(1 - eps^2))
        a_vv = 4 h0 (pi^2 (1 + 2 eps^2) + 32 eps^2 (1 + eps^2)/(1 - eps^2))
        b_uu = 2 pi h0 sqrt(1 - eps^2) (pi^2 (1 + 2 eps^2) - 16 eps^2) / eps
        b_uv = b_vu = -8 h0 (pi^2 (1 + 2 eps^2) - 16 eps^2)
        b_vv = 2 pi h0 (pi^2 (1 - eps^2)^2 + 48 eps^2) / (eps sqrt(1 - eps^2))

    Frame (pinned in ``tests/test_film_coefficients.py`` by finite differences
    of :func:`short_journal_forces`): v is along the static film force on the
    journal (opposite to the external load it carries), u is v turned by
    90 deg *against* the direction of rotation (so the journal turns from u
    towards v); K_ij = -dF_i/dq_j, C_ij = -dF_i/d(dq_j/dt) with F the film
    force on the journal.  Returns ``(K, C)``, 2x2 arrays in (u, v).
    """
    e = eccentricity_ratio
    f0 = short_journal_load(radius, clearance, length, e, eta, surface_speed)[0]
    omega = surface_speed / radius
    pi2 = np.pi**2
    s = np.sqrt(1.0 - e**2)
    h0 = 1.0 / (pi2 * (1.0 - e**2) + 16.0 * e**2) ** 1.5
    a = np.array([
        [4.0 * h0 * (pi2 * (2.0 - e**2) + 16.0 * e**2),
         h0 * np.pi * (pi2 * (1.0 - e**2) ** 2 - 16.0 * e**4) / (e * s)],
        [-h0 * np.pi * (pi2 * (1.0 - e**2) * (1.0 + 2.0 * e**2) + 32.0 * e**2 * (1.0 + e**2)) / (e * s),
         4.0 * h0 * (pi2 * (1.0 + 2.0 * e**2) + 32.0 * e**2 * (1.0 + e**2) / (1.0 - e**2))],
    ])
    buv = -8.0 * h0 * (pi2 * (1.0 + 2.0 * e**2) - 16.0 * e**2)
    b = np.array([
        [2.0 * np.pi * h0 * s * (pi2 * (1.0 + 2.0 * e**2) - 16.0 * e**2) / e, buv],
        [buv, 2.0 * np.pi * h0 * (pi2 * (1.0 - e**2) ** 2 + 48.0 * e**2) / (e * s)],
    ])
    return f0 / clearance * a, f0 / (clearance * omega) * b


# --------------------------------------------------------------------------
# squeeze films


def parallel_disk_squeeze_force(radius, h, eta, dhdt):
    r"""Squeeze force [N] between parallel circular disks (p = 0 at r = radius)::

        F = 3 pi eta R^4 (-dh/dt) / (2 h^3)

    (Hamrock et al. 2004, eq. 12.41); positive (separating) for an approach
    dh/dt < 0.  No sliding velocity.
    """
    return 3.0 * np.pi * eta * radius**4 * (-dhdt) / (2.0 * h**3)


def sphere_plane_squeeze_force(radius, h0, eta, dhdt, domain_radius=np.inf):
    r"""Squeeze force [N] of a sphere (parabolic gap h0 + r^2/(2R)) approaching a plane.

    With p = 0 at r = ``domain_radius`` a (gap h_a = h0 + a^2/(2R))::

        F = 6 pi eta R^2 (-dh/dt) / h0 * (1 - h0/h_a)^2

    which tends to the Reynolds/Taylor result 6 pi eta R^2 (-dh/dt)/h0 for
    a -> infinity (Hamrock et al. 2004, sec. 12.6).  For two spheres use
    R = R1 R2/(R1 + R2).  No sliding velocity.
    """
    ratio = 0.0 if np.isinf(domain_radius) else h0 / (h0 + domain_radius**2 / (2.0 * radius))
    return 6.0 * np.pi * eta * radius**2 * (-dhdt) / h0 * (1.0 - ratio) ** 2


# --------------------------------------------------------------------------
# rigid isoviscous rolling cylinder (Martin)


@dataclass(frozen=True)
class MartinSolution:
    """Rigid isoviscous cylinder with the Reynolds exit condition (see :func:`martin_rigid_cylinder`)."""

    x_exit: float  # [m], p = dp/dx = 0
    load: float  # [N/m]
    coefficient: float  # load * h0 / (eta u_m R)  (4.896 for an infinite inlet)
    x_inlet: float
    radius: float
    h0: float
    eta: float
    mean_speed: float

    def pressure(self, x):
        """Pressure [Pa] at x (zero outside [x_inlet, x_exit])."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        b = np.sqrt(2.0 * self.radius * self.h0)
        xi_in, xi_e = self.x_inlet / b, self.x_exit / b
        scale = 12.0 * self.eta * self.mean_speed * b / self.h0**2
        out = np.zeros_like(x)
        for i, xx in enumerate(x / b):
            if xi_in < xx < xi_e:
                out[i] = scale * integrate.quad(_martin_dp, xi_in, xx, args=(xi_e,), epsabs=1e-14, epsrel=1e-12)[0]
        return out


def _martin_dp(xi, xi_e):
    return 1.0 / (1.0 + xi**2) ** 2 - (1.0 + xi_e**2) / (1.0 + xi**2) ** 3


def martin_rigid_cylinder(radius, h0, eta, mean_speed, x_inlet=-np.inf) -> MartinSolution:
    r"""Rigid cylinder over a plane, isoviscous, Reynolds exit condition (Martin 1916).

    h = h0 (1 + xi^2), x = sqrt(2 R h0) xi, p(x_inlet) = 0 and p = dp/dx = 0 at
    the exit xi_e::

        dp/dxi = 12 eta u_m sqrt(2 R h0)/h0^2 [1/(1 + xi^2)^2 - (1 + xi_e^2)/(1 + xi^2)^3]

    xi_e by brentq on p(xi_e) = 0 (0.4751 for an infinite inlet), load by
    W = -int x dp/dx dx (quad).  For x_inlet -> -infinity
    W = 4.896 eta u_m R / h0 per unit length (Martin 1916; Hamrock et al. 2004,
    eq. 17.28 with u_m = (u_a + u_b)/2).  ``mean_speed`` u_m = (U1 + U2)/2.
    """
    b = np.sqrt(2.0 * radius * h0)
    xi_in = x_inlet / b
    kw = dict(epsabs=1e-14, epsrel=1e-12, limit=200)

    def exit_condition(xi_e):
        return integrate.quad(_martin_dp, xi_in, xi_e, args=(xi_e,), **kw)[0]

    xi_e = optimize.brentq(exit_condition, 1e-6, 2.0, xtol=1e-14)
    # W = int p dx = -int x dp/dx dx  (p vanishes at both ends)
    I = integrate.quad(lambda s: s * _martin_dp(s, xi_e), xi_in, xi_e, **kw)[0]
    coef = -24.0 * I  # W h0 / (eta u_m R)
    load = coef * eta * mean_speed * radius / h0
    return MartinSolution(xi_e * b, load, coef, x_inlet, radius, h0, eta, mean_speed)


# --------------------------------------------------------------------------
# finite-width inclined slider: Fourier series in y


def finite_slider_load(h_in, h_out, length, width, eta, mean_speed, n_terms=81, n_points=2000):
    r"""Load [N] of a finite-width plane inclined slider, by Fourier series in y.

    x in [0, length] (inlet at 0, h = h_in + (h_out - h_in) x/length), y in
    [0, width], p = 0 on all four edges, u_m = ``mean_speed`` along +x.
    With p = sum_n P_n(x) sin(n pi y / width) the Reynolds equation
    (h^3 p_x)_x + h^3 p_yy = 12 eta u_m h' splits into ODEs (Pinkus &
    Sternlicht 1961, sec. 3-4)::

        (h^3 P_n')' - (n pi/width)^2 h^3 P_n = 12 eta u_m h' 4/(n pi)   (n odd; 0 for n even)
        P_n(0) = P_n(length) = 0,
        W = sum_n (2 width/(n pi)) int_0^length P_n dx.

    Each ODE is solved by a conservative second-order finite difference on
    ``n_points`` and ``2 n_points`` intervals, Richardson-extrapolated (error
    ~1e-9 relative); the series is truncated after ``n_terms`` terms (terms
    fall off like n^-4).
    """
    dh = (h_out - h_in) / length

    def mode_integral(n, N):
        x = np.linspace(0.0, length, N + 1)
        dx = x[1] - x[0]
        lam = n * np.pi / width
        h3 = (h_in + dh * x) ** 3
        hm3 = (h_in + dh * 0.5 * (x[1:] + x[:-1])) ** 3  # at midpoints
        # interior unknowns 1..N-1
        main = -(hm3[:-1] + hm3[1:]) / dx**2 - lam**2 * h3[1:-1]
        off = hm3[1:-1] / dx**2
        A = sp.diags([off, main, off], [-1, 0, 1], format="csc")
        rhs = np.full(N - 1, 12.0 * eta * mean_speed * dh * 4.0 / (n * np.pi))
        P = np.zeros(N + 1)
        P[1:-1] = spla.spsolve(A, rhs)
        return integrate.trapezoid(P, x)

    total = 0.0
    for n in range(1, n_terms + 1, 2):
        i1 = mode_integral(n, n_points)
        i2 = mode_integral(n, 2 * n_points)
        total += 2.0 * width / (n * np.pi) * (i2 + (i2 - i1) / 3.0)
    return total


# --------------------------------------------------------------------------
# 1-D mass-conserving (JFO) slider, semi-analytic


@dataclass(frozen=True)
class JFOSlider:
    """Steady 1-D JFO film, see :func:`jfo_slider` (SI units).

    ``flux`` q [m^2/s]; ``x_rupture``/``x_reformation`` [m] (None for a full
    film); ``load`` = int_0^L (p - p_ref) dx [N/m].
    """

    flux: float
    x_rupture: float | None
    x_reformation: float | None
    load: float
    length: float
    gap: object
    eta: float
    mean_speed: float
    p_in: float
    p_out: float
    p_cav: float
    breakpoints: tuple

    def _points(self, a, b):
        return [t for t in self.breakpoints if a < t < b] or None

    def _rise(self, a, b):
        """int_a^b dp/dx dx with the film's flux (full film)."""
        if b <= a:
            return 0.0
        f = lambda s: 12.0 * self.eta * (self.mean_speed * self.gap(s) - self.flux) / self.gap(s) ** 3
        scale = 12.0 * self.eta * abs(self.mean_speed) * self.length / float(self.gap(0.0)) ** 2  # [Pa]
        return integrate.quad(f, a, b, points=self._points(a, b), epsabs=1e-13 * scale, epsrel=1e-12, limit=400)[0]

    def pressure(self, x):
        """Pressure [Pa] at x."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        out = np.empty_like(x)
        for i, s in enumerate(x):
            if self.x_rupture is None or s <= self.x_rupture:
                out[i] = self.p_in + self._rise(0.0, s)
            elif s < self.x_reformation:
                out[i] = self.p_cav
            else:
                out[i] = self.p_cav + self._rise(self.x_reformation, s)
        return out

    def fluid_fraction(self, x):
        """theta: 1 in the full film, 2 q/(U h) = q/(u_m h) in the cavity."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        theta = np.ones_like(x)
        if self.x_rupture is not None:
            cav = (x > self.x_rupture) & (x < self.x_reformation)
            theta[cav] = self.flux / (self.mean_speed * self.gap(x[cav]))
        return theta


def jfo_slider(gap, length, eta, mean_speed, p_in, p_out, p_cav=0.0, breakpoints=(), p_ref=0.0) -> JFOSlider:
    r"""Steady 1-D mass-conserving (JFO) film with one cavity, semi-analytic.

    Film x in [0, length], gap ``gap(x)`` [m] (vectorised callable, smooth
    between ``breakpoints``), p(0) = p_in, p(length) = p_out, cavitation
    pressure p_cav, ``mean_speed`` u_m = (U_lower + U_upper)/2 > 0.  In 1-D the
    volume flux is the same everywhere (JFO; Fowell et al. 2007)::

        q = -h^3 p'/(12 eta) + u_m h          (full film, theta = 1)
        q = u_m h theta,  p = p_cav            (cavity)

    - inlet zone [0, x_c]: p = p_in + int_0^x 12 eta (u_m h - q)/h^3;
      p >= p_cav there requires q <= Q(x) = (p_in - p_cav + 12 eta u_m I2(x))
      / (12 eta I3(x)), I_k = int_0^x h^-k.  If the full film (q from
      p(length) = p_out) stays above p_cav it is the answer; otherwise
      q = min_x Q(x) and the rupture x_c is the minimiser: either a smooth
      point where Q' = 0, i.e. p = p_cav and p' = 0 (u_m h(x_c) = q), or a
      gap discontinuity (the pocket edge), where p' < 0 upstream;
    - cavity (x_c, x_r): theta = q/(u_m h) <= 1;
    - reformation x_r: the outlet zone p = p_out - int_x^length 12 eta
      (u_m h - q)/h^3 reaches p_cav (brentq); flux continuity u_m h theta = q
      holds there by construction.

    Integrals by scipy quad (with the breakpoints); a smooth minimum of Q is
    where Q' = 0, which reduces to u_m h(x) = Q(x) (brentq); roots by brentq.
    Raises ``ValueError`` if the one-cavity structure does not fit (theta > 1
    in the cavity, or no reformation).
    """
    bps = tuple(sorted(float(b) for b in breakpoints))
    kw = dict(epsabs=0.0, epsrel=1e-12, limit=400)

    def I(k, a, b):
        pts = [t for t in bps if a < t < b] or None
        return integrate.quad(lambda s: gap(s) ** (-k), a, b, points=pts, **kw)[0]

    mk = lambda q, xr, xc: JFOSlider(q, xc, xr, 0.0, length, gap, eta, mean_speed, p_in, p_out, p_cav, bps)

    # full film
    I2L, I3L = I(2, 0.0, length), I(3, 0.0, length)
    q_ff = (p_in - p_out + 12.0 * eta * mean_speed * I2L) / (12.0 * eta * I3L)

    def Q(x):
        if x <= 0.0:
            return np.inf
        return (p_in - p_cav + 12.0 * eta * mean_speed * I(2, 0.0, x)) / (12.0 * eta * I(3, 0.0, x))

    # candidates for min Q: smooth stationary points and both sides of each breakpoint
    edges = [0.0] + [b for b in bps if 0.0 < b < length] + [length]
    cands = []
    for a, b in zip(edges[:-1], edges[1:]):
        xs = np.linspace(a, b, 201)[1:]
        xs[-1] = b - 1e-12 * length
        qs = np.array([Q(s) for s in xs])
        cands += [(qs[-1], xs[-1])]
        j = int(np.argmin(qs))
        if 0 < j < len(xs) - 1:
            # stationary point of Q: p_up' = 0 there, i.e. u_m h(x) = Q(x)
            g = lambda s: mean_speed * gap(s) - Q(s)
            xc = optimize.brentq(g, xs[j - 1], xs[j + 1], xtol=1e-15 * length)
            cands.append((Q(xc), xc))
    q_min, x_c = min(cands)
    if q_ff <= q_min * (1.0 + 1e-12):
        sol = mk(q_ff, None, None)
    else:
        q = q_min

        outlet = mk(q, None, None)

        def p_down(x):
            return p_out - outlet._rise(x, length)

        xs = np.linspace(length, x_c, 400)
        vals = np.array([p_down(s) - p_cav for s in xs])
        neg = np.flatnonzero(vals < 0)
        if neg.size == 0:
            raise ValueError("jfo_slider: the outlet film never reaches p_cav (no reformation)")
        k = neg[0]
        x_r = optimize.brentq(lambda s: p_down(s) - p_cav, xs[k], xs[k - 1], xtol=1e-15 * length)
        sol = mk(q, x_r, x_c)
        xcav = np.linspace(x_c, x_r, 200)[1:-1]
        if np.any(sol.fluid_fraction(xcav) > 1.0 + 1e-9):
            raise ValueError("jfo_slider: fluid fraction > 1 in the cavity; the one-cavity structure does not fit")
    # load: full-film zones by quad of p, cavity exactly
    pts = sorted(set(bps + tuple(t for t in (sol.x_rupture, sol.x_reformation) if t is not None)))
    pts = [t for t in pts if 0.0 < t < length]
    load = integrate.quad(lambda s: sol.pressure(s)[0] - p_ref, 0.0, length, points=pts or None,
                          epsabs=0.0, epsrel=1e-10, limit=400)[0]
    return JFOSlider(sol.flux, sol.x_rupture, sol.x_reformation, load, length, gap, eta, mean_speed,
                     p_in, p_out, p_cav, bps)
