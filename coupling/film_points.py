r"""Point kinds of film maps: what one map point solves, and the contact laws around it.

A *point kind* (:class:`PointKind`, registry :data:`KINDS`) tells the map
machinery (:mod:`coupling.maps`) the default axes of a map, the names of its
outputs and a module-level ``evaluate(params, point) -> {output: float}`` that
solves one film.  ``params`` is a plain dict of SI floats and strings
(``default_params()`` of each kind); ``point`` maps axis names to values.  A
point that cannot be solved raises :class:`~lubrication.errors.ConvergenceError`
naming the point.

=========================  ===================================================
kind                       film
=========================  ===================================================
``ball_ball``              two equal balls of paper B (Zhang et al. 2024,
                           Symmetry 16, 741) approaching through an oil film:
                           Reynolds FEM on a graded polar disk, K and C by the
                           perturbation equations
``ehl_ball_inner_race``    6206 ball / inner race EHL point contact (paper B)
``ehl_ball_outer_race``    6206 ball / outer race EHL point contact (paper B)
``ehl_roller_race``        tapered roller / inner race EHL line contact of
                           paper A (Wu, Xu & Deng 2018), for the whole roller
                           length (per slice: scale by the slice's share)
=========================  ===================================================

Ball-ball film (kind ``ball_ball``)
-----------------------------------
Gap (parabolic, equal balls of radius R, R_eff = R/2)::

    h(r) = h0 + r^2/(2 R_eff),       v = -dh0/dt  (> 0: the balls approach)

The *piezoviscous squeeze number* ``Lambda = 3 alpha eta0 R_eff v / h0^2`` [-]
is alpha times the central pressure of the rigid isoviscous squeeze film, so
every (h0, Lambda) point has a solution: a rigid film with a Barus oil has none
beyond Lambda = 1 (below, closed form), and in (h0, v) that boundary is the
curve v = h0^2/(3 alpha eta0 R_eff) (3.8e-4 m/s at h0 = 0.05 um, 0.15 m/s at
1 um, 15 m/s at 10 um for paper B's oil), which no rectangular (h0, v) grid
avoids.  Beyond Lambda ~ 1 the film pressure is high enough to deform the
balls: that is the EHL squeeze regime, where the paper puts the film
stiffness in series with Hertz (:func:`lubrication.laws.collision.series_stiffness`).
:func:`squeeze_number` and :func:`approach_speed` convert.

Polar axes (the map's coordinates).  Entrainment has its own number,
``E = 3 alpha eta0 u_e sqrt(2 R_eff h0) / h0^2`` (:func:`entrainment_number`):
in the Reynolds source 12 eta (u_e x/R_eff - v) over the contact width
sqrt(2 R_eff h0) the rolling term has the pressure scale 3 eta u_e
sqrt(2 R_eff h0)/h0^2 where the squeeze term has 3 eta R_eff v/h0^2.  Scaling
r by sqrt(2 R_eff h0), h by h0 and p by 1/alpha turns the film (on the disk of
h_a = 1000 h0, meshed in proportion) into a problem in (Lambda, E) alone:
F/h0, K, C h0 and p_max depend on (Lambda, E) only (measured: equal to 9
digits at h0 = 0.05, 1 and 50 um).  In (Lambda, E) the film has a *cone*
at the origin: isoviscous, F is homogeneous of degree 1, F = E Phi(Lambda/E),
so with entrainment the approach-side film is full (F independent of u_e)
only while Lambda/E is above a threshold, and the separating film cavitates
more and more as Lambda/E falls.  On a Cartesian (Lambda, u_e) grid that cone
sits in the cells next to Lambda = 0, u_e = 0 at every gap (where it is, in
u_e, moves as h0^-1.5): measured errors of the earlier map up to 59 % (F),
123 % (C) there, with medians of 0.1 %.  The map's axes are therefore

- "Central gap [m]" h0 (log, 2 nodes): a pure scale (F ~ h0, K ~ h0^0,
  C ~ h0^-1, p_max ~ h0^0: exact power laws, interpolated exactly in
  log-log);
- "Pressure number [-]" rho = sqrt(Lambda^2 + E^2) (log): alpha times the
  combined pressure scale; F ~ rho (and C ~ rho^0) in the isoviscous limit,
  the piezoviscous rise towards the pole near rho = 1 on top; below the
  axis' first node (1e-3) the isoviscous scaling F, K, p_max ~ rho, C
  constant holds to ~1e-4 (I(L)/L = 1 + L/6 + ...);
- "Squeeze angle [rad]" theta = atan2(Lambda, E) (linear): pi/2 pure
  approach, 0 pure rolling, negative separating; every output is smooth in
  theta (no cone).  A separating film carries no load at all below the
  onset angle -atan(sqrt(h_a/h0 - 1)) = -88.19 deg
  (:func:`separation_onset_angle`, exact: the source is >= 0 on the whole
  disk); the axis starts at -80 deg, where F is 2.6e-3 of the pure squeeze
  force of the same rho, so that every output is > 0 on the grid and is
  interpolated in log space (towards the onset log F bends over steeply and
  the thin loaded crescent at the inlet edge is resolved by few elements:
  errors of 15 % measured between -85 and -80 deg).  Below -80 deg the film
  force is negligible (a caller takes it as 0, as for a pure separation).

The perturbation coefficients K and C of a partly cavitated film carry a
discretisation noise from the cavitation boundary crossing the elements:
measured between neighbouring squeeze angles 2.5 deg apart (rho = 0.5,
separating side), +-2-4 % on the default 24 x 24 mesh, +-0.3 % on the fine
48 x 32 mesh; the shipped map is built at ``resolution = "fine"``.

:func:`polar_numbers` / :func:`polar_speeds` convert (h0, v, u_e) <-> (h0,
rho, theta); a point may also be given by "Squeeze number [-]" or "Approach
speed [m/s]" with "Entrainment speed [m/s]".  The approach and entrainment
speeds of a map point are closed forms of its coordinates
(:func:`ball_ball_derived`), not tabulated.

Entrainment from the bearing kinematics: neighbouring balls spin the same way
(both roll on the inner race), so at the gap their surfaces move in
*opposite* directions, each at the ball's surface speed about its own centre
(11.5 m/s at paper B's 10,000 rpm: the race entrainment speed of
:func:`lubrication.laws.bearing.entrainment_speed`).  The mean (entraining) velocity
u_e = (u_1 + u_2)/2 is zero for equal spins and equals R (omega_A -
omega_B)/2 for unequal ones (a 1 % spin difference: 0.058 m/s); the sliding
speed u_2 - u_1 ~ 2 x 11.5 m/s is large but, for a rigid Newtonian film, does
not enter the pressure (the Reynolds equation sees only u_m); it makes the
friction ``"Friction per sliding speed [N s/m]"`` = int eta(p)/h dA, which
the dynamics multiply by the actual sliding speed.  The film is squeeze
dominated.  (Measured limit, smoke mesh: at h0 = 0.05 um and u_e = 0.1 m/s,
E = 1.7, the rolling pressure alone reaches the Barus pole and the Reynolds
Newton iteration fails for Lambda >= 0.8; the default rho <= 0.9 converges
at every squeeze angle.)

The physical range of v: the paper gives no ball-ball approach speeds.  Ball
centres orbit at omega_c d_m/2 = 9.6 m/s (10,000 rpm); a 1-10 % speed
difference between a ball in the loaded zone and a slowed one gives 0.01 to
1 m/s; the default rho axis (up to 0.9) covers v up to 0.9 h0^2/(3 alpha eta0
R_eff): 0.14 m/s at 1 um, 14 m/s at 10 um, and u_e up to 0.9 h0^1.5/(3 alpha
eta0 sqrt(2 R_eff)): 0.053 m/s at 0.05 um, 1.5 m/s at 0.5 um.

Solver: :func:`lubrication.reynolds.solve` (P2 triangles on a polar disk whose
ring radii are r_k = r_d sinh(b k/n)/sinh(b), b = 4, so that the ring spacing
follows the pressure) with Reynolds (Swift-Stieber) cavitation at
``cavitation_pressure`` when the film may cavitate (separation or entrainment;
for a pure approach the pressure is positive and the film full); ``p = 0``
(ambient) at the disk edge r_d, where the gap is ``domain_gap_ratio`` x h0
(default 1000: r_d = sqrt(2 R_eff h0 999) = 2.2 mm at h0 = 1 um).  For h0 >
4.8 um the disk is wider than the ball radius: the map is then the film of the
parabolic gap, as in the classical formulas; the part beyond r = R carries
(isoviscous) (h0/H)(1 - H/h_a)^2/(1 - h0/h_a)^2 of the force, H = h0 + R,
i.e. 0.9 % at h0 = 50 um and nothing below 4.8 um.  K = -dF/dh0 and C = dF/dv = -dF/d(dh0/dt) from
:func:`lubrication.reynolds.film_coefficients` (mode ``h0``).  The Newton
iteration starts from the closed-form piezoviscous squeeze pressure (below),
which makes 3-6 iterations.

Closed forms (verification; :func:`squeeze_force_barus`).  Rigid isoviscous
squeeze film with p = 0 at r_d (gap h_a there): from (1/r)(r h^3 p')' = 12 eta
dh/dt, r h^3 p' = -6 eta v r^2 and dh = r dr/R_eff::

    p(r) = 3 eta v R_eff (1/h^2 - 1/h_a^2)
    F    = 2 pi R_eff int_{h0}^{h_a} p dh = 6 pi eta v R_eff^2 / h0 (1 - h0/h_a)^2

(:func:`lubrication.closed_form.sphere_plane_squeeze_force`); with h_a/h0 =
1000 the truncation lowers F by 0.2 % against the infinite film.  Barus
viscosity, incompressible: the reduced pressure q = (1 - exp(-alpha p))/alpha
obeys the isoviscous equation, so p = -ln(1 - alpha q_iso)/alpha and, with
x = h0/h, x_a = h0/h_a::

    F = (2 pi R_eff h0/alpha) int_{x_a}^1 -ln(1 - Lambda (x^2 - x_a^2)) dx/x^2
      -> (2 pi R_eff h0/alpha) [2 sqrt(Lambda) artanh(sqrt(Lambda)) + ln(1 - Lambda)]   (x_a -> 0)

finite (2 ln 2 of the scale) at the pole Lambda = 1 where the central
pressure is infinite; I(L)/L = sum_k L^k/((k + 1)(2k + 1)) = 1 + L/6 + ...
(1.107 at L = 0.5, 1.275 at 0.9).  Dowson-Higginson compressibility adds
about 1 % (measured against an ODE shooting solve, tests/test_ball_film.py).

Signs for the dynamics: "Force [N]" > 0 pushes the balls apart; K > 0 and
C > 0; the force on ball B from ball A is F along the line of centres from A
to B.  Cost (2-core machine, other work running): 0.10 s per point (smoke),
0.16 s (default), ~0.45 s (fine); the default map (19 x 12 x 3 = 684
points) in about 110 s on one core.

EHL contacts (kinds ``ehl_*``)
------------------------------
:func:`lubrication.ehl.solve_ehl` with the load given (load balance),
Barus + Dowson-Higginson oil of paper B (Table 1) or paper A's grease as its
base oil, traction from the limiting-shear law (tau_L0 = 5 MPa, slope 0.08:
mineral-oil values, the papers give none for the race contacts).  Axes: load
Q [N] (log), entrainment speed u_e [m/s] (log), slide-to-roll ratio [-]
(log, positive; traction only: the isothermal pressure does not depend on
sliding, so each (Q, u_e) is solved once and cached per process).  Outputs:
central and minimum film thickness, "Film stiffness [N/m]" K = -dF/dh00 and "Film
damping [N s/m]" C = -dF/d(dh00/dt) (h00 the rigid-body separation: K
includes the elastic bodies, i.e. it is the stiffness of the lubricated
contact, close to Hertz 1.5 Q/delta at heavy load; ball races: central secants
of steady solves at +-10 % load, ``coefficients = "secant"``, because the tangent jumps by up to
5-8 % between neighbouring light-load points as outlet nodes cavitate, see
:func:`_ehl_secant_coefficients`), "Approach [m]" = -h00,
"Traction coefficient [-]".  ``evaluate`` also returns the node maximum
"Maximum pressure [Pa]", which is not tabulated: on the default grids the
outlet pressure spike is one node wide (roller, 257 nodes: the spike node at
1.7-2.5 x its neighbours), so its height is a discretisation artefact that
jumps as the spike moves past the nodes (interpolation errors of 5 % median,
23-67 % max over the roller map; 1.6 %/7 % on the ball races), not a function
of (Q, u_e) that a map can hold; at light roller loads the spike sits 3
nodes from the centre, so the pressure at the centre node is not smooth
either.  Grids: see :data:`EHL_RESOLUTIONS`; default
axes chosen where the solver converges on every node (the EHL Newton
iteration fails for light, strongly piezoviscous contacts: roller M < ~1.5,
i.e. u_e > ~18 m/s at 5-11 kN, beyond paper A's 2000-5000 rpm = 4.4-11 m/s;
ball races at M < 30 with u_e > 6 m/s on short
inlets) -- see :func:`ehl_load_response` for the fallbacks.

Inlet length (ball races).  The film is fed from the inlet; a domain that
starts too close to the contact starves it.  Measured on paper B's races
(22 Nov 2026, 6.4 cells per b_x, |y| <= 1.5 b_y; change of h_c against an
inlet at -38.5 b_x): inlet at -6 b_x (the earlier default): inner race -9.0 %
at 50 N / 30 m/s, -2.8 % at 50 N / 6 m/s, -1.4 % at 245 N / 13.4 m/s, -0.4 %
at 1200 N / 30 m/s (outer race -8.0, -2.7, -1.3, -0.6 %); -13.5 b_x: -0.66 %
(inner, 50 N / 30 m/s); -18.5 b_x: -0.30 % inner / -0.13 % outer there and
< 0.1 % elsewhere.  At the worst corner (inner, 50 N / 30 m/s) the other
outputs against the -38.5 inlet: -6: K +20 %, C +20 %, traction +25 %,
h_min -8.6 %; -18.5: K +1.6 %, C +1.6 %, traction +1.6 %, h_min -0.3 %.
The ball races' ``x_min`` is therefore -18.5 with the node spacing of the
resolution kept (:func:`_ehl_grid`: 129 x 25 nodes at "default", the
contact's nodes at the same x/b as on the old 49 x 25 grid).  Heavy loads
(M > ~500) on the long inlet stall from the nested-iteration start and are
started from the reference-inlet (-6) solution, prolonged
(:func:`_short_inlet_start`).  Known limit, the side extent y_max = 1.5 b_y
(kept: a wider domain costs 3-5 x per solve): its p = 0 boundary feeds the
film from the sides.  Measured with the -18.5 inlet, y_max 1.5 -> 5 b_y
(dy kept): outer race h_c -4.4 % at 50 N / 30 m/s (monotone from 2 b_y:
-0.05, -3.1, -3.2, -4.0, -4.4 % at 2, 2.5, 3, 4, 5 b_y), +0.8 % at 50 N /
6 m/s, +0.2 % at 245 N / 13.4 m/s, +0.06 % at 1200 N / 30 m/s; inner race
-3.1 % at 50 N / 30 m/s (+0.4 % at 2.5 b_y, then -3 % at 4-5 b_y), +0.5 %
at 50 N / 6 m/s, +0.1 % at 245 N / 13.4 m/s.  The rigid-body approach h00
moves by 0.06-0.36 um at 50 N.  So at the light-load, high-speed corner
(M < ~50) the maps' h_c is still up to ~4 % high against an unbounded
domain; from ~250 N or below ~15 m/s it is within 1 %.

Traction axis.  With the limiting-shear law tau = min(eta(p) s u_e/h, tau_L0 +
gamma p) the traction coefficient mu(s) (s the slide-to-roll ratio) is
Newtonian, mu = s u_e int eta/h dA/Q, only below s_c = min(tau_L h/(eta u_e))
over the contact; above, the limited area spreads from the pressure peak
outwards.  With Barus at GPa pressures s_c is tiny and moves by orders of
magnitude with the load (measured: paper B's inner race at 156 N, 13 m/s:
linear up to 3e-9, then a sigmoid in log s up to ~1e-5, then a slow rise
0.05 -> 0.07 to s = 0.1; the sigmoid reaches ~1e-4 at 50 N, 6 m/s).  On a
linear axis through s = 0 that is a step at 0 at every load (errors 27 %
next to 0 in the earlier maps; a cell [0, s_1] holds the step at heavy loads
whatever s_1).  In log s and log mu the curve is smooth along s, but the
sigmoid front moves by ~2 decades of s from one load node to the next, so
between load nodes it is not: measured on the inner race (11 random (Q,
u_e), 3 SRR nodes per decade) max errors 34 % with the axis from 1e-6,
30 % from 1e-5, 3.4 % from 1e-4, 1.9 % from 1e-3 (roller: 0.8 %, 0.5 %).
The axis is log from SRR_MIN = 1e-3 to 0.1 with 3 nodes per decade; a caller
extends it linearly below, mu(s) = mu(1e-3) s/1e-3, and by mu(-s) = -mu(s)
(exact, isothermal).  Physically the viscous isothermal law is not the
traction at such small slip anyway: the oil's shear elasticity G keeps the
shear stress linear in s (Johnson & Tevaarwerk 1977) up to s_e = tau_L
h/(2 G a), 1e-4..1e-3 for these contacts (tau_L ~ 85 MPa, h ~ 0.5-2 um, a ~
0.15-0.3 mm, G ~ 0.3-1 GPa), and the dynamics' closed-form traction
regularises over 0.02.

Contact law of paper B (section 2.2)
------------------------------------
The paper's extracted equations are garbled; what is implemented and how it
was rebuilt:

- eq. (8), printed "K v = 1 K L + 1 K C 1 + K f C v = C f": the equivalent
  stiffness of film and Hertz contact *in series*, K_v = (1/K_L + 1/K_C)^-1
  (plus the one-side film term K_f the paper adds, which is again a
  stiffness in series with the same Hertz term, eq. 15), and C_v = C_f the
  film damping.  Rebuilt from the physics: the film and the elastic bodies
  carry the same force and their compressions add, so compliances add:
  :func:`lubrication.laws.collision.series_stiffness` ``K = K_film K_H/(K_film + K_H)``; the damping of
  a dashpot in series with a spring is not a plain damping, but the paper
  takes C_v = C_f (film damping alone) and so do we
  (:func:`lubrication.laws.collision.series_film_hertz`).
- eqs. (9)/(13)/(14): Hertz stiffness of the ball-ball contact.  For two
  equal balls the contact is circular (kappa = 1, J1 = J2 = pi/2 in the
  paper's elliptic integrals) and Hertz gives (Johnson 1985, eq. 4.23)
  Q = (4/3) E* sqrt(R_eff) delta^(3/2), K_H = dQ/d delta = 2 E* sqrt(R_eff
  delta) = 1.5 Q/delta (:func:`lubrication.laws.collision.hertz_force`).
- eqs. (10)-(12), the collision phases: elastic (Hertz) loading; elastic-
  plastic loading beyond first yield (the paper's "yield stress" sigma and
  a force linear in delta, eq. 11); recovery (eq. 12: a Hertz law in
  delta - delta_sigma, a residual indentation).  That is Thornton's (1997,
  J. Appl. Mech. 64, 383) model, implemented as :func:`lubrication.laws.collision.thornton_force` with
  first yield at p0 = 1.6 Y (Johnson 1985, sec. 6.2, nu = 0.3)
  (:func:`lubrication.laws.collision.yield_onset`).
- eq. (17), the film friction coefficient, printed "mu = 3 eta U h e^(alpha
  p)(alpha p - 1) + 1 alpha^2 p^3": Newtonian Barus shear eta0 exp(alpha p)
  U/h integrated over a Hertzian pressure p0 sqrt(1 - r^2/a^2) and divided
  by the load gives mu = 3 eta0 U [e^(alpha p0)(alpha p0 - 1) + 1]/(h alpha^2
  p0^3) (:func:`lubrication.laws.collision.barus_hertz_friction_coefficient`): the printed formula with
  p = p0.
- eqs. (19)-(21), film rupture: the friction coefficient is the fluid value
  weighted by the film's share of the load plus the boundary value mu_b
  weighted by the asperity share (:func:`lubrication.laws.collision.mixed_friction_coefficient`).  The
  paper's fit of the asperity load share against the film parameter
  lambda ("17 e^(-2.84 lambda) + 1.44e-4 (lambda - 2)^1.1 ... 4 lambda^7.8")
  cannot be rebuilt from the extraction; the share is an input here.

Every contact-law function takes and returns plain floats (no numpy arrays,
no objects), so that :mod:`dynamics` can port it to numba line by line.
"""
from __future__ import annotations

import logging
import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

from lubrication.errors import ConvergenceError, InputError, unknown_choice

from .parameters import printed, si

log = logging.getLogger(__name__)


# ---------------------------------------------------------------- registry


@dataclass(frozen=True)
class AxisDef:
    """One map axis: ``name`` with unit, default range [lo, hi] (SI), ``n`` nodes, ``scale`` "log"/"linear".

    ``explicit``: optional default nodes (increasing, from ``lo`` to ``hi``, ``n`` of them) where the
    function needs them (e.g. denser towards a pole); empty: uniform in x (linear) or log x (log)."""

    name: str
    lo: float
    hi: float
    n: int
    scale: str
    explicit: tuple = ()

    def __post_init__(self):
        if self.scale not in ("log", "linear"):
            raise unknown_choice(f"axis {self.name!r} scale", self.scale, ("log", "linear"))
        if not self.hi > self.lo or self.n < 2:
            raise InputError(f"axis {self.name!r}: needs lo < hi and n >= 2 (got {self.lo}, {self.hi}, {self.n})")
        if self.scale == "log" and not self.lo > 0:
            raise InputError(f"axis {self.name!r}: a log axis needs lo > 0 (got {self.lo})")
        if self.explicit:
            x = np.asarray(self.explicit, dtype=float)
            if (x.size != self.n or x[0] != self.lo or x[-1] != self.hi or not np.all(np.diff(x) > 0)):
                raise InputError(f"axis {self.name!r}: explicit nodes must be n = {self.n} increasing values "
                                 f"from lo = {self.lo} to hi = {self.hi}")

    def nodes(self) -> np.ndarray:
        if self.explicit:
            return np.asarray(self.explicit, dtype=float)
        if self.scale == "log":
            return np.geomspace(self.lo, self.hi, self.n)
        return np.linspace(self.lo, self.hi, self.n)


@dataclass(frozen=True)
class PointKind:
    """A family of film solves tabulated by a map (see the module docstring)."""

    name: str
    description: str
    axes: tuple
    outputs: tuple
    evaluate: Callable
    default_params: Callable
    field: Callable | None = None
    # closed-form quantities of a point (not tabulated: exact functions of the axes), e.g. the
    # approach and entrainment speeds of a ball_ball point: derived(params, point) -> {name: float}
    derived: Callable | None = None
    # outputs that are signed in physics and stored without log even where the map's axes keep them > 0
    # (the traction coefficient, odd in the slide-to-roll ratio: the dynamics extend it by sign and
    # linearly below the axis and read it with logv = 0)
    signed: tuple = ()


# ---------------------------------------------------------------- paper data
# The kinds' default parameters come from the papers' parameter sets (coupling.parameters): paper B
# (Zhang2024: Tables 1, 2, 4) for the ball kinds, paper A (Wu2018: Table 1, figure 5) for the roller.
BALL_RADIUS = si("Zhang2024", "ball_radius")
BALL_DIAMETER = si("Zhang2024", "ball_diameter")
PITCH_DIAMETER_6206 = si("Zhang2024", "pitch_diameter")
INNER_GROOVE_RADIUS = si("Zhang2024", "inner_groove_radius")
OUTER_GROOVE_RADIUS = si("Zhang2024", "outer_groove_radius")
N_BALLS = si("Zhang2024", "n_balls")
BALL_MODULUS, BALL_POISSON = si("Zhang2024", "ball_modulus"), si("Zhang2024", "ball_poisson")
RING_MODULUS, RING_POISSON = si("Zhang2024", "ring_modulus"), si("Zhang2024", "ring_poisson")
OIL_ETA0 = si("Zhang2024", "viscosity")
OIL_ALPHA = si("Zhang2024", "pressure_viscosity")
OIL_RHO0 = si("Zhang2024", "density")
PAPER_B_AXIAL_LOAD = si("Zhang2024", "axial_load")
SHAFT_SPEED_B = printed("Zhang2024", "speed", "rpm") * 2 * math.pi / 60  # rad/s: the film-solution speed
ROLLER_MEAN_DIAMETER = si("Wu2018", "roller_mean_diameter")
ROLLER_PITCH_DIAMETER = si("Wu2018", "pitch_diameter")
ROLLER_INNER_CONTACT_ANGLE = math.radians(printed("Wu2018", "inner_contact_angle", "deg"))
ROLLER_EFFECTIVE_LENGTH = si("Wu2018", "effective_length")
ROLLER_MODULUS, ROLLER_POISSON = si("Wu2018", "steel_modulus"), si("Wu2018", "steel_poisson")
ROLLER_EYRING_STRESS = 5e6  # Pa, Reynolds-Eyring tau0 of the roller map (assumed; ehl_roller_race_default_params)
GREASE_ALPHA = si("Wu2018", "pressure_viscosity")
ROLLER_BASE_OIL_ETA0 = si("Wu2018", "base_oil_viscosity")  # assumed (paper A gives none)
ROLLER_BASE_OIL_RHO0 = si("Wu2018", "base_oil_density")  # assumed
SHAFT_SPEED_A = printed("Wu2018", "inner_speed", "rpm") * 2 * math.pi / 60  # rad/s, figure 5


def _reduced_modulus(E1, nu1, E2, nu2):
    from lubrication.laws.contact import reduced_modulus

    return reduced_modulus(E1, nu1, E2, nu2)


# ====================================================================== ball-ball film

BALL_BALL_RESOLUTIONS = {
    # name: (rings, sectors, element).  Measured (isoviscous squeeze, h_a/h0 = 1000,
    # force against the closed form; central pressure): smoke 16 x 16: -3.3e-3, +2.0e-3;
    # default 24 x 24: -6.9e-4, +5.7e-4; fine 48 x 32: -9.1e-5, +2.4e-5.
    "smoke": (16, 16, "P2"),
    "default": (24, 24, "P2"),
    "fine": (48, 32, "P2"),
}
VISCOSITY_LAWS = ("barus", "roelands", "constant")
DENSITY_LAWS = ("dowson_higginson", "incompressible")
RING_GRADING = 4.0  # b of r_k = r_d sinh(b k/n)/sinh(b); measured best of 2..7 for the squeeze film

PRESSURE_NUMBER = "Pressure number [-]"
SQUEEZE_ANGLE = "Squeeze angle [rad]"
_THETA_LO = math.radians(-80.0)
# Polar axes (module docstring).  The gap is a pure scale (exact power laws, which the two end nodes
# interpolate exactly in log-log; the accuracy points still solve at random gaps); rho: log nodes,
# denser towards the Barus pole near 1; theta: every 15 deg on the approach side, 5 deg on the
# separating side (partly cavitated: K and C curve more) and 2.5 deg next to the axis' end, where log F
# bends over towards the onset at -88.19 deg.  Measured with 16 angles (10 deg steps from -60 to -30,
# 5 deg below): max errors F 2.0 %, K 2.6 %, C 3.1 % (at -59 deg), p_max 2.5 % (at -79 deg).
BALL_BALL_AXES = (
    AxisDef("Central gap [m]", 5e-8, 5e-5, 2, "log"),
    AxisDef(PRESSURE_NUMBER, 1e-3, 0.9, 12, "log",
            (1e-3, 3e-3, 0.01, 0.03, 0.1, 0.2, 0.3, 0.45, 0.6, 0.7, 0.8, 0.9)),
    AxisDef(SQUEEZE_ANGLE, _THETA_LO, 0.5 * math.pi, 20, "linear",
            tuple(math.radians(d) for d in (-80, -77.5, -75, -72.5, -70, -65, -60, -55, -50, -45, -40, -30, -15, 0,
                                            15, 30, 45, 60, 75, 90))),
)
BALL_BALL_OUTPUTS = (
    "Force [N]", "Stiffness [N/m]", "Damping [N s/m]", "Minimum film thickness [m]", "Maximum pressure [Pa]",
    "Friction per sliding speed [N s/m]",
)


def ball_ball_default_params() -> dict:
    """Paper B's ball-ball film: balls of Table 2, oil of Table 1 (SI; keys in :func:`evaluate_ball_ball`)."""
    return {
        "ball_radius": BALL_RADIUS,
        "eta0": OIL_ETA0,
        "alpha": OIL_ALPHA,
        "rho0": OIL_RHO0,
        "viscosity_law": "barus",
        "density_law": "dowson_higginson",
        "cavitation_pressure": 0.0,
        "domain_gap_ratio": 1000.0,
        "resolution": "default",
    }


def _get(params, key, default=None):
    if key in params:
        return params[key]
    if default is None:
        raise InputError(f"film point parameter {key!r} is missing "
                         "(give it, or start from the kind's default_params())")
    return default


def effective_radius(params) -> float:
    """R_eff = R/2 [m] of two equal balls."""
    return 0.5 * float(_get(params, "ball_radius"))


def squeeze_number(h0: float, v: float, params) -> float:
    """Lambda = 3 alpha eta0 R_eff v/h0^2 [-]: alpha times the central pressure of the rigid isoviscous squeeze film."""
    return 3.0 * float(params["alpha"]) * float(params["eta0"]) * effective_radius(params) * v / (h0 * h0)


def approach_speed(h0: float, squeeze: float, params) -> float:
    """v [m/s] (> 0: approach) of squeeze number ``squeeze`` at gap ``h0`` (inverse of :func:`squeeze_number`)."""
    return squeeze * h0 * h0 / (3.0 * float(params["alpha"]) * float(params["eta0"]) * effective_radius(params))


def entrainment_number(h0: float, ue: float, params) -> float:
    """E = 3 alpha eta0 |u_e| sqrt(2 R_eff h0)/h0^2 [-]: alpha times the rolling-pressure scale.

    The entrainment counterpart of :func:`squeeze_number` (module docstring, "Polar axes"):
    the Reynolds source 12 eta (u_e dh/dx + dh/dt) = 12 eta (u_e x/R_eff - v) over the
    contact width sqrt(2 R_eff h0) gives the pressure scales 3 eta R_eff v/h0^2 (squeeze)
    and 3 eta u_e sqrt(2 R_eff h0)/h0^2 (rolling); their ratio is Lambda/E.  The film is
    symmetric in x, so the sign of u_e does not matter.
    """
    return 3.0 * float(params["alpha"]) * float(params["eta0"]) * abs(ue) * math.sqrt(
        2.0 * effective_radius(params) * h0) / (h0 * h0)


def polar_numbers(h0: float, v: float, ue: float, params) -> tuple:
    """``(rho, theta)`` of a ball_ball point: rho = sqrt(Lambda^2 + E^2) [-], theta = atan2(Lambda, E) [rad].

    theta = pi/2: pure approach (squeeze), 0: pure rolling, -pi/2: pure separation
    (:func:`squeeze_number`, :func:`entrainment_number`).
    """
    lam, e = squeeze_number(h0, v, params), entrainment_number(h0, ue, params)
    return math.hypot(lam, e), math.atan2(lam, e)


def polar_speeds(h0: float, rho: float, theta: float, params) -> tuple:
    """``(v, u_e)`` [m/s] of gap ``h0``, pressure number ``rho`` and squeeze angle ``theta`` (inverse of
    :func:`polar_numbers`; u_e >= 0, exactly 0 at theta = +-pi/2)."""
    lam, e = rho * math.sin(theta), rho * math.cos(theta)
    if abs(math.cos(theta)) < 1e-12:
        e = 0.0
    k = 3.0 * float(params["alpha"]) * float(params["eta0"])
    return approach_speed(h0, lam, params), e * h0 * h0 / (k * math.sqrt(2.0 * effective_radius(params) * h0))


def separation_onset_angle(params) -> float:
    """Squeeze angle [rad] below which a separating film carries no load: -atan(sqrt(h_a/h0 - 1)).

    The Reynolds source 12 eta (u_e x/R_eff - v) is >= 0 on the whole disk r <= r_d when the
    separation speed -v >= u_e r_d/R_eff; then p = 0 is the solution (a pressure >= 0 with a
    source >= 0 has its maximum on the boundary, where p = 0), i.e. |Lambda|/E >= r_d/sqrt(2
    R_eff h0) = sqrt(h_a/h0 - 1) (31.6 for the default domain_gap_ratio 1000: theta = -88.19 deg).
    The same holds for any viscosity and density law (the argument uses only the sign of the source).
    """
    return -math.atan(math.sqrt(float(_get(params, "domain_gap_ratio", 1000.0)) - 1.0))


def ball_ball_derived(params: dict, point: dict) -> dict:
    """Closed-form quantities of a ball_ball point: "Approach speed [m/s]", "Entrainment speed [m/s]",
    "Squeeze number [-]", "Entrainment number [-]" (not tabulated: exact functions of the axes)."""
    h0, v, ue = _point_speeds(params, point)
    return {"Approach speed [m/s]": v, "Entrainment speed [m/s]": ue,
            "Squeeze number [-]": squeeze_number(h0, v, params),
            "Entrainment number [-]": entrainment_number(h0, ue, params)}


def _point_speeds(params, point) -> tuple:
    """``(h0, v, u_e)`` of a ball_ball point given on the polar axes or by speeds (module docstring)."""
    h0 = float(point["Central gap [m]"])
    if not h0 > 0:
        raise InputError(f"ball_ball point: 'Central gap [m]' = {h0!r} must be > 0")
    if PRESSURE_NUMBER in point:
        rho, theta = float(point[PRESSURE_NUMBER]), float(point[SQUEEZE_ANGLE])
        if abs(theta) > 0.5 * math.pi and abs(theta) - 0.5 * math.pi < 1e-9:  # "90 deg" rounded
            theta = math.copysign(0.5 * math.pi, theta)
        if not rho >= 0 or not -0.5 * math.pi <= theta <= 0.5 * math.pi:
            raise InputError(f"ball_ball point: {PRESSURE_NUMBER!r} = {rho!r} must be >= 0 and {SQUEEZE_ANGLE!r} = "
                             f"{theta!r} in [-pi/2, pi/2]")
        v, ue = polar_speeds(h0, rho, theta, params)
        return h0, v, ue
    if "Approach speed [m/s]" in point:
        v = float(point["Approach speed [m/s]"])
    else:
        v = approach_speed(h0, float(point["Squeeze number [-]"]), params)
    return h0, v, float(point.get("Entrainment speed [m/s]", 0.0))


def squeeze_force_barus(h0: float, squeeze: float, alpha: float, radius_eff: float, gap_ratio: float = np.inf) -> float:
    """Rigid Barus squeeze-film force [N] of a parabolic gap (incompressible, no entrainment).

    F = (2 pi R_eff h0/alpha) int_{x_a}^1 -ln(1 - Lambda (x^2 - x_a^2)) dx/x^2,
    x_a = 1/``gap_ratio`` (module docstring); the closed form
    2 sqrt(L) artanh(sqrt(L)) + ln(1 - L) for an infinite film, else scipy
    quad.  ``squeeze`` = Lambda in (-inf, 1/(1 - x_a^2)]; Lambda -> 0 gives
    the isoviscous 6 pi eta v R_eff^2/h0 (1 - x_a)^2.
    """
    scale = 2.0 * math.pi * radius_eff * h0 / alpha
    L = float(squeeze)
    if not np.isfinite(gap_ratio):
        if L >= 1.0 or L <= 0.0:
            raise InputError(f"squeeze number = {L!r}: the infinite-film closed form needs 0 < Lambda < 1")
        s = math.sqrt(L)
        return scale * (2.0 * s * math.atanh(s) + math.log1p(-L))
    from scipy.integrate import quad

    xa = 1.0 / gap_ratio
    val, _ = quad(lambda x: -math.log1p(-L * (x * x - xa * xa)) / (x * x), xa, 1.0, epsabs=0.0, epsrel=1e-12, limit=200)
    return scale * val


def _lubricant(params):
    import lubrication as lub

    law = _get(params, "viscosity_law", "barus")
    eta0 = float(_get(params, "eta0"))
    if law == "barus":
        visc = lub.Barus(eta0, float(_get(params, "alpha")))
    elif law == "roelands":
        visc = lub.Roelands(eta0, alpha=float(_get(params, "alpha")))
    elif law == "constant":
        visc = lub.ConstantViscosity(eta0)
    else:
        raise unknown_choice("viscosity_law", law, VISCOSITY_LAWS)
    dlaw = _get(params, "density_law", "dowson_higginson")
    rho0 = float(_get(params, "rho0", OIL_RHO0))
    if dlaw == "dowson_higginson":
        dens = lub.DowsonHigginson(rho0)
    elif dlaw == "incompressible":
        dens = lub.Incompressible(rho0)
    else:
        raise unknown_choice("density_law", dlaw, DENSITY_LAWS)
    tau0 = params.get("eyring_stress")  # absent or None: Newtonian
    return lub.Lubricant(visc, dens, None if tau0 is None else float(tau0))


def polar_disk(radius: float, rings: int, sectors: int, grading: float = RING_GRADING):
    """Triangular mesh of the disk r <= ``radius`` on ``rings`` graded rings of ``sectors`` nodes.

    Ring k (1..rings) at r_k = radius sinh(grading k/rings)/sinh(grading);
    alternate rings are turned by half a sector so that the triangles stay
    near-equilateral; a fan of triangles round the centre node.  Boundary
    ``edge``.
    """
    import skfem

    if rings < 2 or sectors < 6:
        raise InputError(f"polar disk rings = {rings}, sectors = {sectors}: need >= 2 and >= 6")
    k = np.arange(1, rings + 1)
    r = radius * np.sinh(grading * k / rings) / np.sinh(grading) if grading > 0 else radius * k / rings
    j = np.arange(sectors)
    th = 2.0 * np.pi * (j[None, :] + 0.5 * ((k[:, None] - 1) % 2)) / sectors  # ring index k - 1 odd: turned
    rings_xy = np.stack([(r[:, None] * np.cos(th)).ravel(), (r[:, None] * np.sin(th)).ravel()])
    pts = np.concatenate([np.zeros((2, 1)), rings_xy], 1)
    idx = lambda ring, jj: 1 + ring * sectors + (jj % sectors)  # noqa: E731
    tris = [[0, idx(0, jj), idx(0, jj + 1)] for jj in range(sectors)]
    for ring in range(rings - 1):
        for jj in range(sectors):
            a, b, c, d = idx(ring, jj), idx(ring, jj + 1), idx(ring + 1, jj), idx(ring + 1, jj + 1)
            # ring + 1 is turned by +half a sector when ring is even, by -half when odd
            tris += [[a, b, c], [b, d, c]] if ring % 2 == 0 else [[a, b, d], [a, d, c]]
    m = skfem.MeshTri(np.ascontiguousarray(pts), np.ascontiguousarray(np.array(tris, dtype=np.int64).T))
    return m.with_boundaries({"edge": m.boundary_facets()})


@dataclass(frozen=True)
class _Start:
    """Starting pressure for :func:`lubrication.reynolds.solve` (what it reads of ``initial``)."""

    pressure_dofs: np.ndarray
    fluid_fraction_dofs: np.ndarray


def _reduced_pressure_inverse(viscosity, q):
    """p(q) with q(p) = int_0^p eta0/eta(s) ds the reduced pressure (tabulated); NaN beyond the pole."""
    eta0 = viscosity.eta0
    if getattr(viscosity, "is_constant", False):
        return np.asarray(q, dtype=float)
    p = np.concatenate([[0.0], np.geomspace(1e2, 1e10, 1500)])
    ratio = eta0 / viscosity(p)
    qt = np.concatenate([[0.0], np.cumsum(0.5 * (ratio[1:] + ratio[:-1]) * np.diff(p))])
    out = np.interp(q, qt, p, right=np.nan)
    return np.where(np.asarray(q) < 0, 0.0, out)


def _ball_ball_setup(params, point):
    import lubrication as lub

    h0, v, ue = _point_speeds(params, point)
    res = _get(params, "resolution", "default")
    if res not in BALL_BALL_RESOLUTIONS:
        raise unknown_choice("resolution", res, list(BALL_BALL_RESOLUTIONS))
    rings, sectors, element = BALL_BALL_RESOLUTIONS[res]
    Reff = effective_radius(params)
    ratio = float(_get(params, "domain_gap_ratio", 1000.0))
    if not ratio > 1:
        raise InputError(f"domain_gap_ratio = {ratio!r} must be > 1")
    rd = math.sqrt(2.0 * Reff * h0 * (ratio - 1.0))
    mesh = polar_disk(rd, rings, sectors)
    lubricant = _lubricant(params)
    pcav = float(_get(params, "cavitation_pressure", 0.0))
    full = ue == 0.0 and v > 0.0 and pcav <= 0.0  # pressure >= 0 everywhere: no cavitation possible
    R = 2.0 * Reff
    film = lub.Film(
        mesh=mesh, gap=lub.SphereSphere(R, R, h0), lubricant=lubricant,
        velocity_lower=(ue, 0.0), velocity_upper=(ue, 0.0), squeeze=-v, element=element,
        cavitation=lub.Cavitation("none" if full else "reynolds", pcav),
        options=lub.SolverOptions(rtol=1e-10, max_iter=60, warm_start_levels=0),
    )
    # start: the closed-form squeeze pressure of the lubricant's reduced pressure
    from lubrication.reynolds import make_basis

    h = h0 + np.sum(make_basis(mesh, element).doflocs ** 2, axis=0) / (2.0 * Reff)
    ha = h0 * ratio
    q_iso = 3.0 * lubricant.viscosity.eta0 * max(v, 0.0) * Reff * (1.0 / h**2 - 1.0 / ha**2)
    p_start = _reduced_pressure_inverse(lubricant.viscosity, q_iso)
    return film, h0, v, ue, p_start


def _point_text(point) -> str:
    return ", ".join(f"{k} = {float(val):.6g}" for k, val in point.items())


def solve_ball_ball(params, point):
    """Solve the ball-ball film at ``point``; returns ``(solution, h0, v, ue)``.

    Raises :class:`ConvergenceError` naming the point if the Reynolds solve
    fails or the piezoviscous film has no solution (beyond the pole).
    """
    import lubrication as lub

    film, h0, v, ue, p_start = _ball_ball_setup(params, point)
    if np.any(np.isnan(p_start)):
        raise ConvergenceError(
            f"ball_ball point ({_point_text(point)}): the rigid piezoviscous film has no solution "
            f"(the isoviscous central pressure times the reduced-pressure limit of the {params.get('viscosity_law')} "
            "law is beyond its pole: the balls deform, an EHL squeeze regime not modelled here)"
        )
    start = _Start(p_start, np.ones_like(p_start))
    try:
        sol = lub.solve(film, initial=start)
    except ConvergenceError as exc:
        raise ConvergenceError(f"ball_ball point ({_point_text(point)}): {exc}") from exc
    return sol, h0, v, ue


def evaluate_ball_ball(params: dict, point: dict) -> dict:
    """One ball-ball film solve (module docstring).

    ``params`` (SI): ``ball_radius`` [m], ``eta0`` [Pa s], ``alpha`` [1/Pa],
    ``rho0`` [kg/m^3], ``viscosity_law`` ("barus", "roelands" with the same
    low-pressure slope alpha, "constant"), ``density_law``
    ("dowson_higginson", "incompressible"), ``cavitation_pressure`` [Pa,
    gauge], ``domain_gap_ratio`` (h at the disk edge over h0), ``resolution``
    ("smoke", "default", "fine").  ``point``: "Central gap [m]", and
    "Squeeze number [-]" or "Approach speed [m/s]" (> 0 approach),
    "Entrainment speed [m/s]" (default 0).

    Returns "Force [N]" (> 0 pushes the balls apart), "Stiffness [N/m]"
    K = -dF/dh0, "Damping [N s/m]" C = dF/dv, "Minimum film thickness [m]",
    "Maximum pressure [Pa]", "Approach speed [m/s]", "Friction per sliding
    speed [N s/m]" (int eta(p)/h dA over the full film).
    """
    from lubrication.reynolds import film_coefficients, interpolate

    sol, h0, v, ue = solve_ball_ball(params, point)
    _, K, C = film_coefficients(sol)
    prob = sol.problem
    pq = np.asarray(interpolate(sol.basis, sol.pressure_dofs)) - sol.film.ambient_pressure
    eta = sol.film.lubricant.viscosity(pq)
    full = np.asarray(interpolate(sol.basis, sol.full_film.astype(float)))
    friction = sol.integrate(np.clip(full, 0.0, 1.0) * eta / prob.h)
    return {
        "Force [N]": float(sol.mode_forces["h0"]),
        "Stiffness [N/m]": float(K[0, 0]),
        "Damping [N s/m]": float(C[0, 0]),
        "Minimum film thickness [m]": float(sol.h_min),
        "Maximum pressure [Pa]": float(sol.p_max),
        "Approach speed [m/s]": float(v),
        "Friction per sliding speed [N s/m]": float(friction),
    }


def field_ball_ball(params: dict, point: dict):
    """The film at ``point`` as a pyvista grid ("Pressure [Pa]", "Film thickness [m]", ...)."""
    sol, *_ = solve_ball_ball(params, point)
    return sol.to_pyvista()


# ====================================================================== EHL contacts

EHL_RESOLUTIONS = {
    # point contacts: (nx, ny) on the reference domain x in [-6, 1.5] b_x, |y| <= 1.5 b_y; line contacts:
    # nx on x in [-20, 3] b.  They fix the node *spacing* in Hertz semi-axes (:func:`_ehl_grid`): a
    # case's longer domain gets proportionally more nodes, so that the contact keeps its nodes per
    # Hertz radius (point default: 6.4 cells per b_x, 8 per b_y; line default 11.1 per b).
    # Measured on paper B's inner contact (Q = 723 N, u_e = 11.54 m/s), lubrication.ehl of
    # 22 Nov 2026 04:45 UTC (Fischer-Burmeister Newton), (h_c, h_min, K, C, s per point with
    # the other core busy): 33 x 17: 1.1152 um, 0.842 um, 1.2735e8 N/m, 1631 N s/m, 4 s;
    # 49 x 25: 1.1217, 0.991, 1.2818e8, 1593, 13 s; 65 x 33: 1.1272, 1.024, 1.2888e8, 1589, 32 s.
    # Roller (20 kN, 6.46 m/s), 129 / 257 / 513 nodes: h_c 4.046 / 3.990 / 3.992 um,
    # K 8.60e8 / 8.02e8 / 7.98e8 N/m, C 3.01e4 / 4.15e4 / 4.43e4 N s/m (the damping converges
    # slowly on line contacts: 257 nodes is 6 % below 513 there).
    "point": {"smoke": (33, 17), "default": (49, 25), "fine": (65, 33)},
    "line": {"smoke": 129, "default": 257, "fine": 513, "finer": 1025, "finest": 2049},
}
# the reference domains of EHL_RESOLUTIONS (Hertz semi-axes): point (x_min, x_max, y_max), line (x_min, x_max)
EHL_REFERENCE_DOMAIN = {"point": (-6.0, 1.5, 1.5), "line": (-20.0, 3.0)}
TRACTION = {"model": "limiting_shear", "limiting_shear_stress": 5e6, "limiting_shear_slope": 0.08}
EHL_OUTPUTS = (
    "Central film thickness [m]", "Minimum film thickness [m]",
    "Film stiffness [N/m]", "Film damping [N s/m]", "Traction coefficient [-]", "Approach [m]",
)


def _ball_race_geometry(race: str, contact_angle: float) -> tuple:
    """(R_x, R_y) [m] of a 6206 ball on its ``race`` at ``contact_angle`` [rad] (lubrication.laws.bearing)."""
    from lubrication.laws import bearing

    groove = INNER_GROOVE_RADIUS if race == "inner" else OUTER_GROOVE_RADIUS
    return bearing.race_radii(BALL_DIAMETER, PITCH_DIAMETER_6206, groove, race, contact_angle)


def _paper_b_contact_angle() -> float:
    """Contact angle [rad] of the 6206 (zero clearance) under paper B's axial load 200 N (lubrication.laws.bearing)."""
    from lubrication.laws import bearing

    r_i, r_o = INNER_GROOVE_RADIUS, OUTER_GROOVE_RADIUS
    e_star = _reduced_modulus(BALL_MODULUS, BALL_POISSON, RING_MODULUS, RING_POISSON)
    K_n = bearing.deflection_constant(BALL_DIAMETER, PITCH_DIAMETER_6206, r_i, r_o, 0.0, e_star)
    return bearing.thrust_contact_angle(PAPER_B_AXIAL_LOAD, N_BALLS, BALL_DIAMETER, r_i, r_o, K_n, 0.0)


def _ehl_ball_params(race: str) -> dict:
    alpha_c = _paper_b_contact_angle()  # 9.03 deg
    rx, ry = _ball_race_geometry(race, alpha_c)
    return {
        "contact": "point",
        "radius_x": rx,
        "radius_y": ry,
        "e_star": _reduced_modulus(BALL_MODULUS, BALL_POISSON, RING_MODULUS, RING_POISSON),
        "eta0": OIL_ETA0,
        "alpha": OIL_ALPHA,
        "rho0": OIL_RHO0,
        "viscosity_law": "barus",
        "density_law": "dowson_higginson",
        "length": 0.0,
        # inlet at -18.5 b_x: h_c within 0.3 % of an unbounded inlet over the map's axes (module docstring,
        # "Inlet length"); -6 starved the film by up to 9 % at 50 N, 30 m/s
        "x_min": -18.5, "x_max": 1.5, "y_max": 1.5,
        "traction_model": TRACTION["model"],
        "limiting_shear_stress": TRACTION["limiting_shear_stress"],
        "limiting_shear_slope": TRACTION["limiting_shear_slope"],
        # +-10 %: on the 129 x 25 grid the +-5 % secants still jitter by +-2.3 % between neighbouring
        # light loads (outer race, 50-94 N at 27 m/s: deviations from a smooth fit in log Q), +-10 %
        # by +-1.1 %, +-20 % by +-0.7 %; the bias of the wider secant is 0.1 % (+-10 %) / 0.3 % (+-20 %)
        "coefficients": "secant", "secant_step": 0.1,
        "resolution": "default",
    }


def ehl_ball_inner_race_default_params() -> dict:
    """6206 ball / inner race of paper B (Tables 1, 2, 4), contact angle 9.03 deg (Fa = 200 N, zero clearance)."""
    return _ehl_ball_params("inner")


def ehl_ball_outer_race_default_params() -> dict:
    """6206 ball / outer race of paper B (Tables 1, 2, 4), contact angle 9.03 deg (Fa = 200 N, zero clearance)."""
    return _ehl_ball_params("outer")


def ehl_roller_race_default_params() -> dict:
    """Paper A roller / inner race line contact (Table 1; cases/ehl_roller_slice.toml for every number).

    Grease treated as its base oil (as in cases/ehl_roller_slice.toml):
    eta0 = 0.1 Pa s (assumed: paper A gives no base-oil viscosity), Barus
    with the grease's alpha = 4.662e-8 m^2/N (Table 1), incompressible
    870 kg/m^3, and Eyring shear thinning of the Poiseuille flow with tau0 =
    5 MPa (``eyring_stress``; assumed, the traction's limiting-shear
    intercept; paper A gives none).  R = (D/2)(1 - gamma), gamma = D cos(5
    deg)/d_m.

    Why Eyring (measured 22 Nov 2026, 257 and 1025 nodes): with a Newtonian
    base oil this contact (L = 44-66) has several exact discrete solutions at
    the same load and speed -- starts from 0.8, 0.944, 1.06 and 1.25 times the
    load converge to outlet spikes 0.09 b apart and h_min up to 13 % apart
    (10 kN, 4 m/s), on every grid from 257 to 2049 nodes, so h_min, the
    damping and the approach were not functions of (load, speed) that a map
    could hold.  Capping the viscosity (1e6 ... 1e12 Pa s) or a
    Dowson-Higginson density left that unchanged.  The outlet's pressure
    gradient puts the Newtonian Poiseuille shear stress h |dp/dx|/2 at ~1e8
    Pa, far above what an oil carries; with the Eyring flow factor the same
    five starts agree to 1e-13 at 5-20 kN, 3-15 m/s, h_c moves by -1.2 % (10
    kN, 8.84 m/s: 5.177 -> 5.114 um; the inlet is Newtonian) and h_min/h_c
    becomes 0.76 (Newtonian: 0.90-0.95, branch-dependent).
    """
    from lubrication.laws import bearing

    rx = bearing.race_radius_x(ROLLER_MEAN_DIAMETER, ROLLER_PITCH_DIAMETER, ROLLER_INNER_CONTACT_ANGLE, "inner")
    return {
        "contact": "line",
        "radius_x": rx,
        "radius_y": 0.0,
        "e_star": _reduced_modulus(ROLLER_MODULUS, ROLLER_POISSON, ROLLER_MODULUS, ROLLER_POISSON),
        "eta0": ROLLER_BASE_OIL_ETA0,
        "alpha": GREASE_ALPHA,
        "rho0": ROLLER_BASE_OIL_RHO0,
        "viscosity_law": "barus",
        "density_law": "incompressible",
        "eyring_stress": ROLLER_EYRING_STRESS,
        "length": ROLLER_EFFECTIVE_LENGTH,
        "x_min": -20.0, "x_max": 3.0, "y_max": 0.0,
        "traction_model": TRACTION["model"],
        "limiting_shear_stress": TRACTION["limiting_shear_stress"],
        "limiting_shear_slope": TRACTION["limiting_shear_slope"],
        "coefficients": "linearised",
        "resolution": "default",
    }


def _ehl_setup(params, load, speed):
    from lubrication.ehl import EHLContact, EHLOptions, Traction

    line = _get(params, "contact") == "line"
    res = _get(params, "resolution", "default")
    table = EHL_RESOLUTIONS["line" if line else "point"]
    if res not in table:
        raise unknown_choice("resolution", res, list(table))
    traction = Traction(_get(params, "traction_model", "limiting_shear"),
                        float(_get(params, "limiting_shear_stress", 5e6)),
                        float(_get(params, "limiting_shear_slope", 0.08)))
    contact = EHLContact(
        float(params["radius_x"]), None if line else float(params["radius_y"]), float(params["e_star"]),
        _lubricant(params), float(speed), load=float(load), traction=traction)
    grid = _ehl_grid(table[res], line, float(params["x_min"]), float(params["x_max"]), float(params["y_max"]))
    return contact, grid, EHLOptions()


def _ehl_grid(nodes, line: bool, x_min: float, x_max: float, y_max: float):
    """EHLGrid on [x_min, x_max] (x |y| <= y_max) with the node spacing of ``nodes`` on the reference domain.

    The spacing (in Hertz semi-axes) of :data:`EHL_RESOLUTIONS` is kept: nx - 1 = round((x_max - x_min)
    / dx_ref), ny - 1 = round(2 y_max / dy_ref), ny odd (a node row on the centre line).  The x range
    is then moved to start x_max - (nx - 1) dx_ref, so that the nodes sit at the same x/b as on the
    reference domain (the inlet is extended by whole cells: x_min = -18.5 instead of -20 would put
    every node elsewhere).  The reference domain itself gives the table's grid."""
    from lubrication.ehl import EHLGrid

    ref = EHL_REFERENCE_DOMAIN["line" if line else "point"]
    nx_ref = nodes if line else nodes[0]
    dx = (ref[1] - ref[0]) / (nx_ref - 1)
    cells = max(8, int(round((x_max - x_min) / dx)))
    x_lo = x_max - cells * dx
    if line:
        return EHLGrid(nx=cells + 1, x_min=x_lo, x_max=x_max)
    dy = 2 * ref[2] / (nodes[1] - 1)
    ycells = max(2, int(round(2 * y_max / dy)))
    ycells += ycells % 2
    return EHLGrid(nx=cells + 1, ny=ycells + 1, x_min=x_lo, x_max=x_max, y_max=0.5 * ycells * dy)


_EHL_CACHE: dict = {}
_EHL_CACHE_SIZE = 64


def _ehl_key(params, load, speed):
    return (tuple(sorted((k, v) for k, v in params.items())), float(load), float(speed))


def _ehl_secant_coefficients(contact, grid, options, sol, step):
    """K, C as central secants of steady solves: load (1 +- ``step``) Q, and squeeze velocity +-v_s.

    K = -2 step Q / (h00(Q(1 + step)) - h00(Q(1 - step))); at the load Q with a squeeze
    velocity dh00/dt = +-v_s, v_s = ``step`` u_e h_c / b, by implicit differentiation of
    Q(h00, dh00/dt) at fixed Q: C = -K (h00(+v_s) - h00(-v_s)) / (2 v_s).  Each solve
    (lubrication.ehl.solve_ehl, load balance) starts from the steady state ``sol``.
    Why a finite secant and not the tangent: the discrete load F(h00) is only piecewise
    smooth -- each time a node of the outlet (cavitation) boundary changes side, dF/dh00
    jumps.  Measured on paper B's inner contact at 54 N (49 x 25 nodes, x in [-9, 1.5]),
    u_e = 24..28 m/s: the tangent (linearised, or central differences in h00 with step
    1e-3 h_c: they agree to 0.1 %) K = 4.93, 4.87, 4.91, 5.08, 4.80e7 N/m (65 x 33 nodes:
    4.83, 5.28, 4.77, 5.06e7 -- refining does not smooth it); central differences over
    +-3 % h_c 4.91, 4.93, 4.94, 4.91, 4.87e7, C monotone in u_e.  Prescribed-approach solves
    at +-3 % h_c fail at some points (inner race, 288 N, 25 and 30 m/s), and a load step
    moves h00 by ~(2/3) step delta_Hertz >> step h_c, which smooths more.  Each solve tries
    the Newton variants of :func:`ehl_load_response` (same discrete problem), from the
    steady state and from scratch; if all fail, half the step; then the tangent (logged).
    """
    import dataclasses

    from lubrication.ehl import ehl_normal_coefficients, solve_ehl

    w = float(contact.load)
    fields = {f.name for f in dataclasses.fields(options)}
    variants = [{}] + [v for v in ({"first_order_start": "every_grid"}, {"method": "active_set"}) if set(v) <= fields]
    variants += [{"max_step": 1.0, "max_iter": 150}, {"max_step": 0.5, "max_iter": 150}]

    ref_x_min = _longer_inlet(grid, contact.is_line)
    tries = [({}, sol)]
    if ref_x_min is not None:
        # long inlet: the short-inlet solution of the changed contact, prolonged (see ehl_load_response;
        # measured: paper B's inner race at 1200 N, 30 m/s on x in [-18.5, 1.5] b, all four solves
        # stall from the steady state with every Newton variant and converge from this start)
        tries.append(({}, "short inlet"))
    tries += [(v, start) for v in variants for start in (sol, None) if (v, start) != ({}, sol)]

    def h00(**change):
        # the fallbacks of ehl_load_response (other Newton strategies, same discrete problem)
        errors = []
        changed = dataclasses.replace(contact, **change)
        for v, start in tries:
            opts = dataclasses.replace(options, **v)
            try:
                if isinstance(start, str):
                    start = _short_inlet_start(changed, grid, opts, ref_x_min)
                return solve_ehl(changed, grid, opts, initial=start).h00
            except (ConvergenceError, np.linalg.LinAlgError) as exc:
                errors.append(str(exc))
        raise ConvergenceError(" / ".join(errors[-2:]))

    for st in (step, 0.5 * step):
        try:
            K = -2 * st * w / (h00(load=w * (1 + st)) - h00(load=w * (1 - st)))
            vs = st * contact.mean_speed * sol.central_film_thickness / sol.problem.bx
            C = -K * (h00(squeeze_velocity=contact.squeeze_velocity + vs)
                      - h00(squeeze_velocity=contact.squeeze_velocity - vs)) / (2 * vs)
            return K, C
        except (ConvergenceError, np.linalg.LinAlgError) as exc:
            log.warning("EHL secant coefficients with step %g failed (%s)", st, exc)
    log.warning("EHL secant coefficients failed; using the linearised tangent")
    K, C, _ = ehl_normal_coefficients(contact, grid, options, steady=sol)
    return K, C


def _longer_inlet(grid, line: bool):
    """The reference domain's inlet x_min [Hertz semi-axes] if ``grid`` starts upstream of it (a long
    inlet, whose heavy loads are started from the short-inlet solution), else None."""
    ref_x_min = EHL_REFERENCE_DOMAIN["line" if line else "point"][0]
    return ref_x_min if grid.x_min < ref_x_min - 1e-9 else None


def _short_inlet_start(contact, grid, options, x_min):
    """Start for ``grid``: the steady solution on the same nodes with the inlet cut at ``x_min`` (Hertz
    semi-axes), returned as it is: ``solve_ehl`` interpolates a start from another grid onto its own
    (multilinear, zero upstream of the short inlet)."""
    import dataclasses

    from lubrication import ehl

    cells = int(round((grid.x_max - x_min) * (grid.nx - 1) / (grid.x_max - grid.x_min)))
    dx = (grid.x_max - grid.x_min) / (grid.nx - 1)
    short = dataclasses.replace(grid, nx=cells + 1, x_min=grid.x_max - cells * dx)
    sol = None
    for variant in ({}, {"method": "active_set"}):
        try:
            sol = ehl.solve_ehl(contact, short, dataclasses.replace(options, **variant))
            break
        except (ConvergenceError, np.linalg.LinAlgError) as exc:
            error = exc
    if sol is None:
        raise ConvergenceError(f"short-inlet start: {error}")
    return sol


def ehl_load_response(params: dict, load: float, speed: float) -> dict:
    """EHL solve at element load ``load`` = Q [N] and entrainment speed ``speed`` [m/s] (SRR-independent).

    A line contact carries Q/``length`` per unit length; its stiffness and
    damping are returned for the whole ``length``.  Normal coefficients
    (``params["coefficients"]``)::

        Film stiffness  K = -dF/dh00        (h00 the rigid-body separation, -h00 the approach)
        Film damping    C = -dF/d(dh00/dt)  (at fixed h00)

    - ``"linearised"`` (default): :func:`lubrication.ehl.ehl_normal_coefficients`
      of the EHL module (one extra linear solve about the steady state, the
      cavitated set frozen);
    - ``"load_steps"``: two more steady solves, load (1 + 1e-3) Q and the load
      with a squeeze velocity dh00/dt = v_s = 1e-3 u_e h_c/b; K = -dQ/dh00
      along the steady states and, by implicit differentiation of
      Q(h00, dh00/dt) at fixed Q, C = -K dh00/d(dh00/dt).  A second method:
      measured against the linearised one on paper B's inner contact (smoke
      grid) K +2.0 %, C -0.5 %; paper A's roller (10 kN, 10 m/s) K +0.3 %,
      C +0.2 %;
    - ``"secant"`` (ball races' default): central secants of four steady solves, load
      (1 +- ``secant_step``) Q and squeeze velocity +-``secant_step`` u_e h_c/b
      (:func:`_ehl_secant_coefficients`).

    Cached per process (the slide-to-roll ratio only changes the traction,
    post-processing of the same pressure).
    """
    import dataclasses

    from lubrication.ehl import solve_ehl

    key = _ehl_key(params, load, speed)
    if key in _EHL_CACHE:
        return _EHL_CACHE[key]
    line = params["contact"] == "line"
    length = float(params["length"]) if line else 1.0
    w = float(load) / length
    method = _get(params, "coefficients", "linearised")
    if method not in ("linearised", "load_steps", "secant"):
        raise unknown_choice("coefficients", method, ("linearised", "load_steps", "secant"))
    contact, grid, options = _ehl_setup(params, w, speed)
    text = f"Load [N] = {load:.6g}, Entrainment speed [m/s] = {speed:.6g}"
    # Fallbacks, in order: other Newton strategies on the same discrete problem (the
    # answer does not change), continuation from twice the load, and last a slightly
    # larger domain (changes the film by ~0.2 % at paper B's inner contact; on the roller's
    # 257 nodes h_min and the damping by ~4 % at 5 kN, 6.5 m/s: a point that needs it is
    # discretised differently from its neighbours.  Extending the domain by whole cells
    # instead, so that the contact's nodes stay put, made the two roller points that need this
    # fallback (14.1 kN, 3 m/s; 20 kN, 13.9 m/s) fail altogether, measured 22 Nov 2026).  Measured: paper B's inner contact at
    # Q = 178 N, u_e = 30 m/s on 49 x 25 nodes (M = 120, L = 32) stalls with the default
    # Fischer-Burmeister Newton and converges, to the same h_c to 1e-11, with a
    # first-order start on every grid or with the active-set method; the roller line
    # contact at Q = 14.1 kN, u_e = 30 m/s (M = 3, L = 77) failed with max_step 2, 0.5
    # and 0.25 and converged with 1; light strongly piezoviscous line contacts (M ~ 1-2)
    # converge only from a heavier-load solution.
    fields = {f.name for f in dataclasses.fields(options)}
    variants = [{}]
    if "first_order_start" in fields:
        variants.append({"first_order_start": "every_grid"})
    if "method" in fields:
        variants.append({"method": "active_set"})
    variants += [{"max_step": 1.0, "max_iter": 150}, {"max_step": 0.5, "max_iter": 150}]
    attempts = [(grid, dataclasses.replace(options, **v)) for v in variants]
    ref_x_min = _longer_inlet(grid, line)
    if ref_x_min is not None:
        # a long inlet (ball races: x_min = -18.5): start from the solution on the reference inlet,
        # prolonged (measured: paper B's races at 700-1200 N, M = 480-2700, fail on x in [-18.5, 1.5]
        # from the nested-iteration start with every Newton variant above and converge in 1-2 s from
        # the x_min = -6 solution; the pressure upstream of -6 b is negligible there)
        attempts.insert(1, (grid, options, "short inlet"))
    slow = dataclasses.replace(options, max_step=0.5, max_iter=150)
    if contact.lubricant.eyring_stress is not None:
        # Eyring flow: start from the Newtonian solution of the same point (same grid, so the
        # discretisation stays that of the neighbours; measured on the roller map, 257 nodes:
        # the larger-domain fallback below moved h_c by 2.7 % at 5 kN, 7.7 m/s)
        attempts.append((grid, slow, "newtonian"))
    attempts.append((grid, slow, 2.0))
    if line:
        attempts.append((dataclasses.replace(grid, x_max=grid.x_max + 1.0), slow))
    else:
        attempts.append((dataclasses.replace(grid, y_max=grid.y_max + 0.5), slow))
    errors = []
    for number, attempt in enumerate(attempts):
        grid, options = attempt[:2]
        try:
            start = None
            if len(attempt) > 2 and attempt[2] == "short inlet":
                start = _short_inlet_start(contact, grid, options, ref_x_min)
            elif len(attempt) > 2 and attempt[2] == "newtonian":
                newtonian = dataclasses.replace(contact.lubricant, eyring_stress=None)
                start = solve_ehl(dataclasses.replace(contact, lubricant=newtonian), grid, options)
            elif len(attempt) > 2:
                start = solve_ehl(dataclasses.replace(contact, load=w * attempt[2]), grid, options)
            sol = solve_ehl(contact, grid, options, initial=start)
            if method == "secant":
                K, C = _ehl_secant_coefficients(contact, grid, options, sol, float(_get(params, "secant_step", 0.05)))
            elif method == "linearised":
                from lubrication.ehl import ehl_normal_coefficients

                K, C, _ = ehl_normal_coefficients(contact, grid, options, steady=sol)
            else:
                eps = 1e-3
                sol2 = solve_ehl(dataclasses.replace(contact, load=w * (1 + eps)), grid, options, initial=sol)
                vs = 1e-3 * speed * sol.central_film_thickness / sol.problem.bx
                sq = solve_ehl(dataclasses.replace(contact, squeeze_velocity=vs), grid, options, initial=sol)
                K = -w * eps / (sol2.h00 - sol.h00)
                C = -K * (sq.h00 - sol.h00) / vs
            break
        except (ConvergenceError, np.linalg.LinAlgError) as exc:
            errors.append(str(exc))
            log.info("EHL point (%s): attempt %d failed: %s", text, number + 1, exc)
    else:
        raise ConvergenceError(f"EHL point ({text}): {' / then: '.join(errors)}")
    if number:
        log.info("EHL point (%s) converged at attempt %d (%s)", text, number + 1, options)
    out = {
        "solution": sol,
        "Central film thickness [m]": sol.central_film_thickness,
        "Minimum film thickness [m]": sol.minimum_film_thickness,
        "Maximum pressure [Pa]": sol.maximum_pressure,
        "Film stiffness [N/m]": float(K) * length,
        "Film damping [N s/m]": float(C) * length,
        "Approach [m]": -float(sol.h00),
    }
    if len(_EHL_CACHE) >= _EHL_CACHE_SIZE:
        _EHL_CACHE.pop(next(iter(_EHL_CACHE)))
    _EHL_CACHE[key] = out
    return out


def evaluate_ehl(params: dict, point: dict) -> dict:
    """One EHL contact point: "Load [N]", "Entrainment speed [m/s]", "Slide-to-roll ratio [-]".

    Outputs :data:`EHL_OUTPUTS`; "Traction coefficient [-]" = Couette friction
    over load from the limiting-shear law (tau = min(eta du/h, tau_L0 +
    gamma p), tau_L0 = 5 MPa, gamma = 0.08 by default: mineral-oil values; the
    papers give none for the race contacts), positive for SRR > 0 (u2 > u1),
    exactly odd in SRR (isothermal: the pressure does not depend on sliding).
    """
    import dataclasses

    load = float(point["Load [N]"])
    speed = float(point["Entrainment speed [m/s]"])
    srr = float(point.get("Slide-to-roll ratio [-]", 0.0))
    base = ehl_load_response(params, load, speed)
    sol = base["solution"]
    c = dataclasses.replace(sol.contact, slide_to_roll=srr)
    traction = dataclasses.replace(sol, contact=c).traction_coefficient()
    out = {k: float(v) for k, v in base.items() if k != "solution"}
    out["Traction coefficient [-]"] = float(traction)
    return out


def field_ehl(params: dict, point: dict):
    """The EHL pressure/film field at ``point`` as a pyvista grid."""
    response = ehl_load_response(params, float(point["Load [N]"]), float(point["Entrainment speed [m/s]"]))
    return response["solution"].to_pyvista()


# ====================================================================== registry

# Slide-to-roll ratio: log, 3 nodes per decade from SRR_MIN (traction is odd in the SRR: mu(-s) = -mu(s);
# below SRR_MIN a caller takes mu(SRR_MIN) s/SRR_MIN, see the module docstring, "Traction axis").
SRR_MIN = 1e-3
EHL_SRR_AXIS = AxisDef("Slide-to-roll ratio [-]", SRR_MIN, 0.1, 7, "log")
EHL_BALL_AXES = (
    AxisDef("Load [N]", 50.0, 1200.0, 6, "log"),
    AxisDef("Entrainment speed [m/s]", 6.0, 30.0, 4, "log"),
    EHL_SRR_AXIS,
)
# paper A runs at 2000-5000 rpm: u_e = 4.4-11 m/s on the inner race
EHL_ROLLER_AXES = (
    # 9 x 11 nodes (Eyring flow, 257 nodes): on 5 x 6 the map missed h_c by 3.1 % and the approach by
    # 6.5 % in the light-load, high-speed corner, where inlet shear thinning sets in (h_c at 5 kN grows
    # 4-5 % per speed step between 3.9 and 5.1 m/s against 9-10 % elsewhere); 9 x 11: max 1.8 % / 0.6 %
    AxisDef("Load [N]", 5000.0, 20000.0, 9, "log"),
    AxisDef("Entrainment speed [m/s]", 3.0, 15.0, 11, "log"),
    EHL_SRR_AXIS,
)

KINDS: dict = {
    "ball_ball": PointKind(
        name="ball_ball",
        description=("Oil film between two neighbouring balls of paper B's cage-less 6206 (R = 4.7625 mm, Table 1 "
                     "oil, Barus + Dowson-Higginson): rigid Reynolds FEM squeeze film with entrainment and "
                     "Reynolds cavitation; K = -dF/dh0, C = dF/dv by the perturbation equations; polar axes "
                     "(gap, pressure number, squeeze angle)"),
        axes=BALL_BALL_AXES,
        outputs=BALL_BALL_OUTPUTS,
        evaluate=evaluate_ball_ball,
        default_params=ball_ball_default_params,
        field=field_ball_ball,
        derived=ball_ball_derived,
    ),
    "ehl_ball_inner_race": PointKind(
        name="ehl_ball_inner_race",
        description=("EHL point contact of a 6206 ball with the inner race (paper B: groove radius 4.905 mm, contact "
                     "angle 9.03 deg, E 207/208 GPa, Table 1 oil), limiting-shear traction"),
        axes=EHL_BALL_AXES,
        outputs=EHL_OUTPUTS,
        evaluate=evaluate_ehl,
        default_params=ehl_ball_inner_race_default_params,
        field=field_ehl,
        signed=("Traction coefficient [-]",),
    ),
    "ehl_ball_outer_race": PointKind(
        name="ehl_ball_outer_race",
        description=("EHL point contact of a 6206 ball with the outer race (paper B: groove radius 4.953 mm, contact "
                     "angle 9.03 deg, E 207/208 GPa, Table 1 oil), limiting-shear traction"),
        axes=EHL_BALL_AXES,
        outputs=EHL_OUTPUTS,
        evaluate=evaluate_ehl,
        default_params=ehl_ball_outer_race_default_params,
        field=field_ehl,
        signed=("Traction coefficient [-]",),
    ),
    "ehl_roller_race": PointKind(
        name="ehl_roller_race",
        description=("EHL line contact of paper A's tapered roller (mean diameter 21.305 mm, 42.06 mm effective "
                     "length) with the inner race, grease as its base oil (eta0 0.1 Pa s assumed, alpha 4.662e-8); "
                     "load and stiffness for the whole roller length"),
        axes=EHL_ROLLER_AXES,
        outputs=EHL_OUTPUTS,
        evaluate=evaluate_ehl,
        default_params=ehl_roller_race_default_params,
        field=field_ehl,
        signed=("Traction coefficient [-]",),
    ),
}
