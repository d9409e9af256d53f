r"""Transient elastohydrodynamic impact of two elastic spheres (or a sphere and a flat) in normal approach.

The reference against which quasi-steady film maps of a ball-ball collision are judged: the film is
solved in time, from first approach at an initial gap and speed, through the entrapped dimple, to
rebound with cavitation and separation.

Equations (SI, axisymmetric, r the radius from the line of centres, gauge pressure p)::

    (1/r) d/dr( r rho h^3/(12 eta) dp/dr ) = d(rho h)/dt          (transient Reynolds)
    p = 0 at r = r_out;  p >= 0, G(p) >= 0, p G(p) = 0                (cavitation, complementarity)
    h(r, t) = h0(t) + r^2/(2 R) + w(r, t)                              (film)
    w(r, t) = int_0^r_out p(s, t) W(r, s) s ds                         (elastic half-spaces, 1/E*)
    m dv/dt = F(t) - F_ext,  dh0/dt = v,  F = 2 pi int_0^r_out p r dr  (bodies)

R is the effective radius (R1 R2/(R1 + R2); a ball on a flat: the ball's radius), E* the reduced
modulus (1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2), m the effective mass (m1 m2/(m1 + m2)), h0 the
rigid gap (negative once the undeformed bodies overlap), v = dh0/dt (negative while approaching),
F >= 0 the film force pushing the bodies apart and F_ext an optional constant force pushing them
together (gravity for a drop).  eta(p) and rho(p) are any Newtonian laws of
:mod:`lubedyn.lubrication.laws.lubricant` (Barus, Roelands, Dowson-Higginson).

Where the film would close (h below h_floor = 1e-6 h_start, the dry limit) its conductance is held at
h_floor: the bodies then touch through a vanishing film and the solids carry the load.

Cavitation is the complementarity (Reynolds-type) condition: where the film would need a negative
pressure, p = 0 and the residual G = d(rho h)/dt - div(...) >= 0.  It is *not* mass conserving: the
film that leaves a cavitated region is not tracked (a JFO/Elrod model would carry a fill fraction);
in an impact the cavitated region opens only during rebound, when the gap opens everywhere.

Discretisation
--------------
Uniform radial nodes r_i = i dr, i = 0..N, p_N = 0 at r_out = N dr.  Finite volumes: node i owns
the annulus [r_i - dr/2, r_i + dr/2] (node 0 the disc [0, dr/2]) with area weight
V_i = (b_i^2 - a_i^2)/2; fluxes r_f k_f (p_{i+1} - p_i)/dr on the faces r_f = (i + 1/2) dr, k_f the
mean of the nodes' k = rho h^3/(12 eta).  The pressure is constant on each annulus (the force
F = 2 pi sum V_i p_i), and the deflection of a uniform pressure on a disc of radius a is exact
(Johnson 1985, *Contact Mechanics*, sec. 3.4, combined for both bodies with 1/E*)::

    W_disc(r; a) = 4 a E(r^2/a^2)/(pi E*)                                   (r <= a)
    W_disc(r; a) = 4 r [E(a^2/r^2) - (1 - a^2/r^2) K(a^2/r^2)]/(pi E*)      (r > a)

(K, E the complete elliptic integrals of parameter m, :func:`scipy.special.ellipk` / ``ellipe``), so
that the influence matrix is W_disc(r_i; b_j) - W_disc(r_i; a_j), dense (N+1) x N.  Checked against
Hertz's pressure p0 sqrt(1 - r^2/a^2), whose deflection is pi p0 (2 a^2 - r^2)/(4 a E*) inside the
contact (Johnson eq. 3.42): tests/test_ehl_impact.py.

Time: variable-step BDF2 for d(rho h)/dt and for both kinematic equations (backward Euler on the
first step), fully implicit.  Each step solves for the N pressures and h0 together by a semismooth
Newton iteration on min(p_i, G_i/J_ii) = 0 (the min-function form of the complementarity; J_ii the
diagonal of dG/dp, frozen within an iteration) and the scaled equation of motion, with the exact
dense Jacobian (the elastic influence enters through dk/dh and d(rho h)/dh) and a backtracking line
search; a step whose Newton iteration fails is retried at half the time step (counted in the result).

Energy.  With the complementarity condition, sum over the film of p times the Reynolds equation gives
(summation by parts, p = 0 on the boundary of the pressurised zone) the power balance
d/dt (m v^2/2 + U_el) = -D - F_ext v with the elastic energy U_el = pi sum V_i p_i w_i and the viscous
dissipation of the Poiseuille flow D = 2 pi int h^3/(12 eta) (dp/dr)^2 r dr (incompressible; a
compressible film also stores compression energy).  The result carries both sides: the kinetic
energy lost (from the motion) and the time integral of D (from the film), a check of each other.

Outputs: :class:`ImpactResult` (per step: t, h0, v, central and minimum film, maximum pressure, force,
dissipation rate; at the end: restitution coefficient, energy dissipated, the cost).  The
restitution e = v_out/v_in is taken at the initial gap: after the film has fully cavitated (p = 0
everywhere, no deformation) the motion is ballistic and is continued in closed form to h0 = h_start.

Validation (tests/test_ehl_impact.py, each against something independent; paper B's steel balls,
0.1 m/s unless said):

- Hertz's pressure deflected by the ring influence matrix against Johnson's eq. 3.42: largest error 9.4e-4
  (200 nodes) and 3.6e-4 (400 nodes) of the central deflection, at the contact edge.
- Rigid, isoviscous, slow approach: Reynolds' squeeze force
  (:func:`lubedyn.lubrication.closed_form.sphere_plane_squeeze_force`, finite film)
  within 0.86 % / 0.22 % on 40 / 80 nodes (order 2.0 in dr); 0.67 % below 6 pi eta R^2 v/h0 with
  r_out = 1 mm.
- Dry limit (isoviscous 1e-4 Pa s): largest force -0.67 %, largest approach +0.22 %, time of overlap
  -1.0 % (one step) against Hertz's impact, e = 0.9983 (60 nodes, 100 steps per Hertz duration).
- Energy: with Table 1's viscosity isoviscous and incompressible (e = 0.839), the film's integrated
  dissipation falls short of the kinetic energy lost by 1.23 / 0.38 / 0.14 % at 50 / 100 / 200 steps per
  Hertz duration; Barus (incompressible) 1.95 / 0.74 % at 100 / 200 steps (D is sharply peaked in time
  when the piezoviscous film releases).
- Measured orders: largest force 2.1 in dt; restitution 2.0 and largest force 2.3 in dr.
- Published impact EHL: no case with stated inputs and result numbers was reachable for this work
  (Larsson & Hoglund 1995, J. Tribol. 117:94, and Safa & Gohar 1986, J. Tribol. 108:372: abstracts only;
  Bertin 2024, J. Fluid Mech., arXiv 2308.10754: its scaling and restitution formulas could not be
  retrieved).  What Larsson & Hoglund's abstract states is checked qualitatively: central entrapment,
  cavitation closing in from the periphery in rebound, pressures above the dry impact's and highest
  near the centre just before separation (2.2 p0* with Table 1's oil at 0.1 m/s), the minimum film
  after the largest force (0.11 t_c later).

The start gap matters: the squeeze film dissipates about 6 pi eta0 R^2 v^2 ln 2 per doubling of the gap
(rigid, isoviscous), so the restitution depends logarithmically on ``h_start`` (paper B's balls and oil
at 0.2 m/s: e = 0.904 from 6.5 um, 0.892 from 13 um); compare quasi-steady laws with this reference
from the same start gap.

Cost (one core, 2-core machine shared with other jobs, load 6-7): 0.5-1.5 s per impact at 40-60 nodes
and 100-200 steps per Hertz duration; 5-29 s at 160 nodes and 300 steps (benchmarks/impact_ehl.py).
The dense (N+1)^2 solve per Newton iteration dominates; 3-5 iterations per step.

Hertz impact (Johnson 1985, sec. 11.4): :func:`hertz_impact` gives the closed-form maximum approach
delta* = (15 m v^2/(16 E* R^(1/2)))^(2/5), force (4/3) E* R^(1/2) delta*^(3/2) and duration
(4/5) B(2/5, 1/2) delta*/v = 2.9433 delta*/v (Johnson: 2.94), the dry limit of this solver.
"""
from __future__ import annotations

import logging
import math
import time
import warnings
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg
from scipy.special import ellipe, ellipk

from ..errors import ConvergenceError, InputError, require_positive
from ..laws.contact import HertzImpact, hertz_impact  # noqa: F401  (re-exported)
from ..laws.lubricant import Lubricant

log = logging.getLogger(__name__)


# ---------------------------------------------------------------------------------------------------------
# closed forms


# HertzImpact and hertz_impact are laws (lubedyn.lubrication.laws.contact), imported above for the callers of
# this module


# ---------------------------------------------------------------------------------------------------------
# elasticity


def disc_deflection(r, a, e_star: float):
    """Combined normal deflection [m] at radius ``r`` of two half-spaces under unit pressure on the disc
    of radius ``a`` (module docstring; 0 where a = 0).  e_star = inf: rigid (0)."""
    r = np.asarray(r, dtype=float)
    a = np.asarray(a, dtype=float)
    r, a = np.broadcast_arrays(r, a)
    out = np.zeros(r.shape)
    if not np.isfinite(e_star):
        return out
    inside = (r <= a) & (a > 0)
    outside = (r > a) & (a > 0)
    ai, ri = a[inside], r[inside]
    out[inside] = 4.0 * ai * ellipe((ri / ai) ** 2) / (math.pi * e_star)
    ao, ro = a[outside], r[outside]
    m = (ao / ro) ** 2
    out[outside] = 4.0 * ro * (ellipe(m) - (1.0 - m) * ellipk(m)) / (math.pi * e_star)
    return out


def ring_influence_matrix(n: int, dr: float, e_star: float) -> np.ndarray:
    """Influence matrix (n + 1) x n [m/Pa]: deflection at nodes r_i = i dr (i = 0..n) per unit pressure
    on the annulus of node j (cell [j dr - dr/2, j dr + dr/2], node 0 the disc [0, dr/2])."""
    r = np.arange(n + 1) * dr
    outer = (np.arange(n) + 0.5) * dr
    inner = np.maximum(np.arange(n) - 0.5, 0.0) * dr
    return disc_deflection(r[:, None], outer[None, :], e_star) - disc_deflection(r[:, None], inner[None, :], e_star)


# ---------------------------------------------------------------------------------------------------------
# problem, numerics, result


@dataclass(frozen=True)
class ImpactProblem:
    """Two bodies in normal approach through a film.

    ``radius`` R_eff [m] (R1 R2/(R1 + R2)); ``e_star`` E* [Pa] (``math.inf``: rigid bodies); ``mass``
    m_eff [kg]; ``lubricant`` a Newtonian :class:`Lubricant`; ``speed`` approach speed v_in > 0 [m/s]
    at the initial rigid gap ``h_start`` > 0 [m]; ``force`` F_ext >= 0 [N], constant, pushing the
    bodies together (a drop: m g)."""

    radius: float
    e_star: float
    mass: float
    lubricant: Lubricant
    speed: float
    h_start: float
    force: float = 0.0

    def __post_init__(self):
        require_positive("impact radius [m]", self.radius)
        if not float(self.e_star) > 0:
            raise InputError(f"impact e_star [Pa] = {self.e_star!r} must be > 0 (math.inf: rigid)")
        require_positive("impact mass [kg]", self.mass)
        require_positive("impact speed [m/s]", self.speed)
        require_positive("impact h_start [m]", self.h_start)
        if not (float(self.force) >= 0.0 and math.isfinite(self.force)):
            raise InputError(f"impact force [N] = {self.force!r} must be a finite number >= 0")
        if not isinstance(self.lubricant, Lubricant) or not self.lubricant.is_newtonian:
            raise InputError(f"impact lubricant = {self.lubricant!r} must be a Newtonian Lubricant "
                             "(no eyring_stress, no herschel_bulkley)")

    @property
    def rigid(self) -> bool:
        return not math.isfinite(self.e_star)

    def hertz(self) -> HertzImpact | None:
        """The dry Hertz impact at the approach speed (None for rigid bodies)."""
        return None if self.rigid else hertz_impact(self.radius, self.e_star, self.mass, self.speed)


@dataclass(frozen=True)
class ImpactNumerics:
    """Resolution of :func:`simulate_impact`.

    ``nodes`` N radial intervals; ``r_out`` [m] (None: the larger of 3 Hertz radii and the radius where
    the undeformed gap is 4 h_start); ``dt`` [s] (None: the Hertz duration / ``steps_per_contact``;
    rigid bodies: h_start / speed / ``steps_per_contact``); ``t_max`` [s] (None: 20 times h_start/speed
    plus 10 Hertz durations); ``tol`` relative Newton tolerance; ``max_newton`` iterations per step;
    ``keep_profiles``: store p(r) and h(r) at every step."""

    nodes: int = 160
    r_out: float | None = None
    dt: float | None = None
    steps_per_contact: int = 400
    t_max: float | None = None
    tol: float = 1e-9
    max_newton: int = 40
    keep_profiles: bool = False

    def __post_init__(self):
        if not (isinstance(self.nodes, (int, np.integer)) and 8 <= self.nodes <= 4000):
            raise InputError(f"impact nodes = {self.nodes!r} must be an integer in [8, 4000]")
        for key in ("r_out", "dt", "t_max"):
            value = getattr(self, key)
            if value is not None:
                require_positive(f"impact {key}", value)
        if not (isinstance(self.steps_per_contact, (int, np.integer)) and self.steps_per_contact >= 4):
            raise InputError(f"impact steps_per_contact = {self.steps_per_contact!r} must be an integer >= 4")
        if not 0 < self.tol < 1e-2:
            raise InputError(f"impact tol = {self.tol!r} must lie in (0, 1e-2)")


@dataclass
class ImpactResult:
    """A simulated impact.  Per step (arrays over time, first entry the start): ``t`` [s], ``h0`` rigid
    gap [m], ``v`` dh0/dt [m/s], ``h_central`` h(0) [m], ``h_min`` [m], ``p_max`` [Pa], ``force`` film
    force [N], ``dissipation`` viscous power D [W].  ``r`` nodes [m]; ``p``, ``h`` [Pa, m] per step
    (``keep_profiles``) else None.

    At the end: ``separated`` (the film fully cavitated while the bodies moved apart); ``restitution``
    v_out/v_in at h0 = h_start (NaN if not separated); ``energy_dissipated`` [J] kinetic energy lost
    over the impact (m (v_in^2 - v_out^2)/2, the work of F_ext cancelling between equal gaps);
    ``energy_dissipated_film`` [J] the trapezoidal time integral of D up to separation (the same
    quantity from the film: equal for an incompressible film up to the discretisation); ``seconds``
    wall time; ``steps``; ``newton_iterations`` total; ``halvings`` time steps retried at half size."""

    r: np.ndarray
    t: np.ndarray
    h0: np.ndarray
    v: np.ndarray
    h_central: np.ndarray
    h_min: np.ndarray
    p_max: np.ndarray
    force: np.ndarray
    dissipation: np.ndarray
    separated: bool
    restitution: float
    energy_dissipated: float
    energy_dissipated_film: float
    kinetic_energy_in: float
    seconds: float
    steps: int
    newton_iterations: int
    halvings: int
    p: np.ndarray | None = None
    h: np.ndarray | None = None
    warnings: list = field(default_factory=list)
    units: dict = field(default_factory=lambda: dict(
        r="m", t="s", h0="m", v="m/s", h_central="m", h_min="m", p_max="Pa", force="N", dissipation="W",
        restitution="-", energy_dissipated="J", energy_dissipated_film="J", kinetic_energy_in="J",
        seconds="s"))

    @property
    def force_max(self) -> float:
        """Largest film force [N]."""
        return float(self.force.max())

    @property
    def approach_max(self) -> float:
        """Largest rigid overlap -min(h0) [m]."""
        return float(-self.h0.min())

    def summary(self) -> dict:
        """Scalars of the impact, SI (JSON-ready)."""
        i = int(np.argmax(self.force))
        return dict(restitution=self.restitution, energy_dissipated=self.energy_dissipated,
                    energy_dissipated_film=self.energy_dissipated_film, kinetic_energy_in=self.kinetic_energy_in,
                    force_max=self.force_max, approach_max=self.approach_max,
                    h_min=float(self.h_min.min()), h_central_at_force_max=float(self.h_central[i]),
                    p_max=float(self.p_max.max()), separated=self.separated, seconds=self.seconds,
                    steps=self.steps, newton_iterations=self.newton_iterations, halvings=self.halvings)


#: the film's integrated dissipation may differ from the kinetic energy lost by at most this fraction of the
#: loss (measured: 0.14-1.95 % over 50-200 steps per contact, Barus and isoviscous; tests/test_ehl_impact.py)
ENERGY_BALANCE_TOLERANCE = 0.05


def impact_bound_warnings(restitution: float, lost: float, film: float, kinetic: float) -> list[str]:
    """The bounds an impact's results must respect, one line per one left: the restitution in [0, 1]
    (a passive film cannot return more energy than it got), the energy lost >= 0 and the film's own
    dissipation within :data:`ENERGY_BALANCE_TOLERANCE` of it (an unresolved run otherwise).

    >>> impact_bound_warnings(0.9, 0.19, 0.19, 1.0)
    []
    >>> impact_bound_warnings(1.2, -0.44, 0.0, 1.0)[0].split(" (")[0]
    'restitution 1.2 is outside [0, 1]'
    """
    out = []
    if math.isfinite(restitution) and not 0.0 <= restitution <= 1.0:
        out.append(f"restitution {restitution:.4g} is outside [0, 1] (a passive film returns at most the energy "
                   "it got); refine the time step or the grid")
    if lost < 0.0:
        out.append(f"energy lost {lost:.4g} J is negative; refine the time step or the grid")
    elif lost > 0.0 and abs(film - lost) > ENERGY_BALANCE_TOLERANCE * lost:
        out.append(f"the film's dissipation {film:.4g} J differs from the kinetic energy lost {lost:.4g} J by "
                   f"{abs(film - lost) / lost:.1%} (> {ENERGY_BALANCE_TOLERANCE:.0%}): the run is not resolved; "
                   "refine the time step or the grid")
    return out


# ---------------------------------------------------------------------------------------------------------
# the solver


class _Film:
    """Grid, influence matrix and the residual/Jacobian of one implicit step."""

    def __init__(self, problem: ImpactProblem, n: int, r_out: float):
        self.pb = problem
        self.n = n
        self.dr = dr = r_out / n
        self.r = np.arange(n + 1) * dr  # nodes 0..n, p_n = 0
        outer = (np.arange(n) + 0.5) * dr
        inner = np.maximum(np.arange(n) - 0.5, 0.0) * dr
        self.V = 0.5 * (outer**2 - inner**2)  # int r dr over each node's cell
        self.rf = outer  # faces i + 1/2, i = 0..n-1
        self.K = ring_influence_matrix(n, dr, problem.e_star)  # (n+1) x n
        self.h_rigid = self.r**2 / (2.0 * problem.radius)
        self.visc = problem.lubricant.viscosity
        self.dens = problem.lubricant.density
        self.incompressible = bool(problem.lubricant.density.is_constant)

    def film(self, p, h0):
        """h at the n + 1 nodes, and the full pressure vector (p_n = 0)."""
        return h0 + self.h_rigid + self.K @ p, np.append(p, 0.0)

    def force(self, p) -> float:
        return 2.0 * math.pi * float(self.V @ p)

    def dissipation(self, p, h0) -> float:
        """D = 2 pi sum_f r_f dr (h^3/(12 eta))_f ((p_{i+1} - p_i)/dr)^2 [W]."""
        h, pa = self.film(p, h0)
        c = np.maximum(h, 0.0) ** 3 / (12.0 * self.visc(pa))
        cf = 0.5 * (c[:-1] + c[1:])
        return 2.0 * math.pi * float(np.sum(self.rf * cf * np.diff(pa) ** 2) / self.dr)

    def elastic_energy(self, p, h0) -> float:
        return math.pi * float(self.V @ (p * (self.K[:-1] @ p)))

    def residual(self, p, h0, c, hist_rho_h, hist_h0, hist_v, jac=True):
        """G (n), the scaled motion residual E, and (jac) dG/dp, dG/dh0, dE/dp, dE/dh0.

        d(rho h)/dt = c0 (rho h) + hist_rho_h;  v = c0 h0 + hist_h0;  dv/dt = c0 v + hist_v."""
        pb = self.pb
        n, dr = self.n, self.dr
        h, pa = self.film(p, h0)
        hfloor = 1e-6 * pb.h_start
        hp = np.maximum(h, hfloor)
        rho, drho = self.dens(pa), self.dens.derivative(pa)
        eta, deta = self.visc(pa), self.visc.derivative(pa)
        k = rho * hp**3 / (12.0 * eta)
        kf = 0.5 * (k[:-1] + k[1:])
        dp = np.diff(pa)
        flux = self.rf * kf * dp / dr  # faces 0..n-1 (between i and i+1)
        div = flux.copy()
        div[1:] -= flux[:-1]
        rho_h = rho[:n] * h[:n]
        G = self.V * (c[0] * rho_h + hist_rho_h) - div
        v = c[0] * h0 + hist_h0
        E = (pb.mass * (c[0] * v + hist_v) - self.force(p) + pb.force) / (pb.mass * c[0] ** 2)
        if not jac:
            return G, E
        # dk_i/dp_i (own pressure, through rho and eta) and dk_i/dh_i
        dk_p = k * (drho / rho - deta / eta)
        dk_h = np.where(h > hfloor, 3.0 * k / hp, 0.0)
        # flux_f = rf kf dp_f/dr: d/dp_f = -rf kf/dr + g_f dk_p_f/2, d/dp_{f+1} = rf kf/dr + g_f dk_p_{f+1}/2
        g = self.rf * dp / dr * 0.5
        # dflux_f/dh_j for j = f, f+1
        a_f = g * dk_h[:-1]
        b_f = g * dk_h[1:]
        # d div_i/dh_j: div_i = flux_i - flux_{i-1}
        # j = i: a_i - b_{i-1};  j = i+1: b_i;  j = i-1: -a_{i-1}
        Ad = a_f.copy()
        Ad[1:] -= b_f[:-1]
        Au = b_f  # (i, i+1), i = 0..n-1, column i+1 up to n
        Al = np.zeros(n)
        Al[1:] = -a_f[:-1]  # (i, i-1)
        # dG/dh = V c0 rho (diag) - d div/dh
        Hd = self.V * c[0] * rho[:n] - Ad
        Hu = -Au
        Hl = -Al
        K = self.K
        Jp = Hd[:, None] * K[:n] + Hu[:, None] * K[1:n + 1]
        Jp[1:] += Hl[1:, None] * K[:n - 1]
        # direct dependence on p (tridiagonal)
        dflux_dpf = -self.rf * kf / dr + g * dk_p[:-1]  # d flux_f / d p_f
        dflux_dpf1 = self.rf * kf / dr + g * dk_p[1:]  # d flux_f / d p_{f+1}
        idx = np.arange(n)
        diag = -dflux_dpf.copy()
        diag[1:] += dflux_dpf1[:-1]
        diag += self.V * c[0] * drho[:n] * h[:n]
        Jp[idx, idx] += diag
        Jp[idx[:-1], idx[:-1] + 1] += -dflux_dpf1[:-1]
        Jp[idx[1:], idx[1:] - 1] += dflux_dpf[:-1]
        Jh0 = Hd + Hu
        Jh0[1:] += Hl[1:]
        dE_dp = -2.0 * math.pi * self.V / (pb.mass * c[0] ** 2)
        return G, E, Jp, Jh0, dE_dp, 1.0


def _bdf_coefficients(dt: float, dt_prev: float | None):
    """(c0, c1, c2) of y' ~ c0 y^{n+1} + c1 y^n + c2 y^{n-1}: variable-step BDF2, backward Euler if
    there is no previous step."""
    if dt_prev is None:
        return 1.0 / dt, -1.0 / dt, 0.0
    w = dt / dt_prev
    return (1.0 + 2.0 * w) / ((1.0 + w) * dt), -(1.0 + w) / dt, w * w / ((1.0 + w) * dt)


def _default_numerics(problem: ImpactProblem, numerics: ImpactNumerics):
    hz = problem.hertz()
    h_start = problem.h_start
    r_gap = math.sqrt(2.0 * problem.radius * 4.0 * h_start)
    r_out = numerics.r_out or max(r_gap, 3.0 * hz.radius if hz else 0.0)
    t_scale = hz.duration if hz else h_start / problem.speed
    dt = numerics.dt or t_scale / numerics.steps_per_contact
    t_max = numerics.t_max or (20.0 * h_start / problem.speed + 10.0 * (hz.duration if hz else 0.0))
    return r_out, dt, t_max


def simulate_impact(problem: ImpactProblem, numerics: ImpactNumerics = ImpactNumerics()) -> ImpactResult:
    """Integrate the impact from h0 = h_start, v = -speed until the film has fully cavitated with the
    bodies moving apart, or until h0 returns to h_start, or ``t_max`` (module docstring).  BLAS runs on
    one thread (the dense solves are small: threads only contend)."""
    from threadpoolctl import threadpool_limits

    with threadpool_limits(limits=1, user_api="blas"):
        return _simulate(problem, numerics)


def _simulate(problem: ImpactProblem, numerics: ImpactNumerics) -> ImpactResult:
    start_clock = time.perf_counter()
    r_out, dt_nominal, t_max = _default_numerics(problem, numerics)
    film = _Film(problem, numerics.nodes, r_out)
    n = film.n
    m = problem.mass
    hz = problem.hertz()
    p_scale = hz.pressure if hz else 6.0 * problem.lubricant.viscosity.eta0 * problem.speed * problem.radius \
        / problem.h_start**2
    log.info("impact: R %.4g m, E* %.4g Pa, m %.4g kg, v %.4g m/s, h_start %.4g m; %d nodes on %.4g m, "
             "dt %.4g s", problem.radius, problem.e_star, m, problem.speed, problem.h_start, n, r_out, dt_nominal)

    p = np.zeros(n)
    h0, v = problem.h_start, -problem.speed
    hist = dict(t=[0.0], h0=[h0], v=[v], h_central=[], h_min=[], p_max=[0.0], force=[0.0], dissipation=[0.0])
    hfull, _ = film.film(p, h0)
    hist["h_central"].append(hfull[0])
    hist["h_min"].append(hfull.min())
    profiles_p, profiles_h = ([p.copy()], [hfull.copy()]) if numerics.keep_profiles else (None, None)
    # state for BDF2: current and previous (rho h, h0, v)
    rho_h = film.dens(np.append(p, 0.0))[:n] * hfull[:n]
    prev = None  # (rho_h, h0, v, dt) of the previous level
    t = 0.0
    dt = dt_nominal
    dt_prev = None
    total_newton, halvings, steps = 0, 0, 0
    separated = False
    p_prev = p.copy()
    e_film = 0.0
    d_old = 0.0
    while t < t_max - 1e-9 * dt_nominal:
        dt = min(dt, t_max - t)
        c = _bdf_coefficients(dt, dt_prev if prev is not None else None)
        if prev is None:
            hist_rho_h = c[1] * rho_h
            hist_h0 = c[1] * h0
            hist_v = c[1] * v
        else:
            hist_rho_h = c[1] * rho_h + c[2] * prev[0]
            hist_h0 = c[1] * h0 + c[2] * prev[1]
            hist_v = c[1] * v + c[2] * prev[2]
        # predictor: linear extrapolation
        w = dt / dt_prev if dt_prev else 0.0
        p_guess = np.maximum(p + w * (p - p_prev), 0.0)
        h_guess = h0 + v * dt
        try:
            p_new, h0_new, its = _newton(film, p_guess, h_guess, c, hist_rho_h, hist_h0, hist_v, p_scale,
                                         numerics.tol, numerics.max_newton)
        except ConvergenceError as err:
            if dt < dt_nominal / 1024:
                raise ConvergenceError(f"impact: the step at t = {t:.6g} s failed at dt = {dt:.3g} s: {err}") from err
            dt *= 0.5
            halvings += 1
            log.debug("impact: halving the step at t = %.6g s (%s)", t, err)
            continue
        total_newton += its
        steps += 1
        v_new = c[0] * h0_new + hist_h0
        h_new, pa = film.film(p_new, h0_new)
        rho_h_new = film.dens(pa)[:n] * h_new[:n]
        d_new = film.dissipation(p_new, h0_new)
        e_film += 0.5 * (d_old + d_new) * dt
        d_old = d_new
        prev = (rho_h, h0, v)
        p_prev = p
        rho_h, h0, v, p = rho_h_new, h0_new, v_new, p_new
        t += dt
        dt_prev = dt
        dt = min(2.0 * dt, dt_nominal)
        F = film.force(p)
        hist["t"].append(t)
        hist["h0"].append(h0)
        hist["v"].append(v)
        hist["h_central"].append(h_new[0])
        hist["h_min"].append(h_new.min())
        hist["p_max"].append(p.max())
        hist["force"].append(F)
        hist["dissipation"].append(d_new)
        if numerics.keep_profiles:
            profiles_p.append(p.copy())
            profiles_h.append(h_new.copy())
        if v > 0 and not np.any(p > 0):
            separated = True
            break
        if v > 0 and h0 >= problem.h_start:
            separated = True
            break
    # ballistic continuation to h_start: v_out^2 = v^2 - 2 (F_ext/m) (h_start - h0)
    if separated:
        v_out2 = v * v - 2.0 * problem.force / m * (problem.h_start - h0)
        v_out = math.sqrt(max(v_out2, 0.0))
        restitution = v_out / problem.speed
        e_lost = 0.5 * m * (problem.speed**2 - v_out**2)
    else:
        log.warning("impact: no separation by t_max = %.4g s (h0 %.4g m, v %.4g m/s)", t_max, h0, v)
        restitution = float("nan")
        e_lost = 0.5 * m * (problem.speed**2 - v * v) - problem.force * (problem.h_start - h0) \
            - film.elastic_energy(p, h0)
    seconds = time.perf_counter() - start_clock
    log.info("impact: %d steps, %d Newton iterations, %d halvings, %.2f s; e = %.4f", steps, total_newton,
             halvings, seconds, restitution)
    arr = {k: np.asarray(v_, dtype=float) for k, v_ in hist.items()}
    found = impact_bound_warnings(restitution, e_lost, e_film, 0.5 * m * problem.speed**2)
    for text in found:
        log.warning("impact: %s", text)
    return ImpactResult(warnings=found, r=film.r, separated=separated, restitution=restitution, energy_dissipated=e_lost,
                        energy_dissipated_film=e_film, kinetic_energy_in=0.5 * m * problem.speed**2,
                        seconds=seconds, steps=steps, newton_iterations=total_newton, halvings=halvings,
                        p=np.array(profiles_p) if profiles_p is not None else None,
                        h=np.array(profiles_h) if profiles_h is not None else None, **arr)


def _newton(film: _Film, p, h0, c, hist_rho_h, hist_h0, hist_v, p_scale, tol, max_iter):
    """Semismooth Newton on Phi = [min(p_i, G_i/J_ii), E] (module docstring).  A trial iterate whose
    viscosity overflows (Barus at a wild pressure) has a non-finite residual and is rejected by the line
    search (numpy's overflow warnings and scipy's ill-conditioning warning are silenced here: the
    iteration checks finiteness itself and a failed step is retried at half the time step)."""
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"), warnings.catch_warnings():
        warnings.simplefilter("ignore", scipy.linalg.LinAlgWarning)
        return _newton_iterations(film, p, h0, c, hist_rho_h, hist_h0, hist_v, p_scale, tol, max_iter)


def _newton_iterations(film: _Film, p, h0, c, hist_rho_h, hist_h0, hist_v, p_scale, tol, max_iter):
    n = film.n
    h_scale = film.pb.h_start

    def merit(phi):
        return math.sqrt(float(np.sum((phi[:n] / p_scale) ** 2)) + (phi[n] / h_scale) ** 2)

    def system(p, h0, jac=True):
        out = film.residual(p, h0, c, hist_rho_h, hist_h0, hist_v, jac=jac)
        return out

    G, E, Jp, Jh0, dE_dp, dE_dh0 = system(p, h0)
    for it in range(1, max_iter + 1):
        s = 1.0 / np.maximum(np.diag(Jp), 1e-300)
        active = p <= s * G  # the pressure branch of the min
        phi = np.where(active, p, s * G)
        phi = np.append(phi, E)
        J = np.empty((n + 1, n + 1))
        J[:n, :n] = s[:, None] * Jp
        J[:n, n] = s * Jh0
        ia = np.flatnonzero(active)
        J[ia, :] = 0.0
        J[ia, ia] = 1.0
        J[n, :n] = dE_dp
        J[n, n] = dE_dh0
        # unknowns in units of (p_scale, h_scale), residual rows likewise: a well-scaled matrix
        J[:, n] *= h_scale / p_scale
        J[n, :] *= p_scale / h_scale
        try:
            rhs = phi.copy()
            rhs[n] *= p_scale / h_scale
            dx = -scipy.linalg.solve(J, rhs, check_finite=False)
            dx[n] *= h_scale / p_scale
        except (scipy.linalg.LinAlgError, ValueError) as err:
            raise ConvergenceError(f"singular Newton matrix ({err})") from err
        if not np.all(np.isfinite(dx)):
            raise ConvergenceError("non-finite Newton step")
        scale = max(float(p.max()), 1e-6 * p_scale)
        if float(np.max(np.abs(dx[:n]))) <= tol * scale and abs(dx[n]) <= tol * h_scale:
            return np.maximum(p + dx[:n], 0.0), h0 + dx[n], it  # the Newton correction is below tolerance
        f0 = merit(phi)
        lam = 1.0
        while True:
            p_try = np.maximum(p + lam * dx[:n], 0.0)
            h_try = h0 + lam * dx[n]
            G_t, E_t = system(p_try, h_try, jac=False)
            phi_t = np.append(np.minimum(p_try, s * G_t), E_t)
            if not np.all(np.isfinite(phi_t)):
                f1 = math.inf
            else:
                f1 = merit(phi_t)
            if f1 <= (1.0 - 1e-4 * lam) * f0:
                break
            if lam < 1e-3:
                raise ConvergenceError(f"line search failed (merit {f0:.3g} -> {f1:.3g})")
            lam *= 0.5
        step_p = float(np.max(np.abs(p_try - p))) if n else 0.0
        step_h = abs(h_try - h0)
        p, h0 = p_try, h_try
        if step_p <= tol * scale and step_h <= tol * h_scale and lam == 1.0:
            return p, h0, it
        G, E, Jp, Jh0, dE_dp, dE_dh0 = system(p, h0)
    raise ConvergenceError(f"Newton did not converge in {max_iter} iterations (last step {step_p:.3g} Pa, "
                           f"{step_h:.3g} m)")
