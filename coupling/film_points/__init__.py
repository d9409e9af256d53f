r"""Point kinds of film maps: what one map point solves, and the contact laws around it.

A *point kind* (:class:`PointKind`, registry :data:`KINDS`) tells the map
machinery (:mod:`lubedyn.maps`) the default axes of a map, the names of its
outputs and a module-level ``evaluate(params, point) -> {output: float}`` that
solves one film.  ``params`` is a plain dict of SI floats and strings
(``default_params()`` of each kind); ``point`` maps axis names to values.  A
point that cannot be solved raises :class:`~lubedyn.lubrication.errors.ConvergenceError`
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
``ehl_roller_cone``        tapered roller / cone (inner race) EHL line
                           contact of paper A (Wu, Xu & Deng 2018) per metre
                           of contact, on a line-load axis (per slice:
                           stiffness and damping times the slice length)
``ehl_roller_cup``         the same on the cup (outer race)
``ehl_ball_ball``          two neighbouring balls of paper B through an EHL film
                           (quasi-steady squeeze and entrainment, Roelands,
                           Dowson-Higginson; module ``ehl_ball_ball``: what
                           it reaches and why not the collision states)
``ehl_rib``                roller end / cone rib EHL point contact of paper A
                           per flange load and entrainment speed (module
                           ``rib``: where the solver reaches it)
=========================  ===================================================

The roller kinds replace ``ehl_roller_race`` (the whole 42.06 mm roller at
5-20 kN, 3-15 m/s; :func:`ehl_roller_race_default_params` stays as the point set the solver-limit
tests pin).  Their domain grows with the film (``inlet_film_lengths``, :func:`_film_scaled_domain`)
and a point the solver's own start cannot reach is continued along :data:`CONTINUATION_PATHS`
(shorter inlet, lighter load, lower speed) or from a converged state at 0.9 of its load (recursively,
damped Newton step; :data:`LIGHTER_LOAD_STEP`).  Their traction goes through a map on a normalised slip
(the front of the limiting-shear traction moves by decades of slip between load nodes; see
:func:`evaluate_ehl_line`), their central film is interpolated at x = 0, and their stiffness and damping
are central secants above Moes' M = 0.25 (``secant_min_moes_M``; the linearised tangent below).

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
stiffness in series with Hertz (:func:`lubedyn.lubrication.laws.collision.series_stiffness`).
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
:func:`lubedyn.lubrication.laws.bearing.entrainment_speed`).  The mean (entraining) velocity
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

Solver: :func:`lubedyn.lubrication.reynolds.solve` (P2 triangles on a polar disk whose
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
:func:`lubedyn.lubrication.reynolds.film_coefficients` (mode ``h0``).  The Newton
iteration starts from the closed-form piezoviscous squeeze pressure (below),
which makes 3-6 iterations.

Closed forms (verification; :func:`squeeze_force_barus`).  Rigid isoviscous
squeeze film with p = 0 at r_d (gap h_a there): from (1/r)(r h^3 p')' = 12 eta
dh/dt, r h^3 p' = -6 eta v r^2 and dh = r dr/R_eff::

    p(r) = 3 eta v R_eff (1/h^2 - 1/h_a^2)
    F    = 2 pi R_eff int_{h0}^{h_a} p dh = 6 pi eta v R_eff^2 / h0 (1 - h0/h_a)^2

(:func:`lubedyn.lubrication.closed_form.sphere_plane_squeeze_force`); with h_a/h0 =
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
:func:`lubedyn.lubrication.ehl.solve_ehl` with the load given (load balance),
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
(6.4 cells per b_x, |y| <= 1.5 b_y; change of h_c against an
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
  :func:`lubedyn.lubrication.laws.collision.series_stiffness` ``K = K_film K_H/(K_film + K_H)``; the damping of
  a dashpot in series with a spring is not a plain damping, but the paper
  takes C_v = C_f (film damping alone) and so do we
  (:func:`lubedyn.lubrication.laws.collision.series_film_hertz`).
- eqs. (9)/(13)/(14): Hertz stiffness of the ball-ball contact.  For two
  equal balls the contact is circular (kappa = 1, J1 = J2 = pi/2 in the
  paper's elliptic integrals) and Hertz gives (Johnson 1985, eq. 4.23)
  Q = (4/3) E* sqrt(R_eff) delta^(3/2), K_H = dQ/d delta = 2 E* sqrt(R_eff
  delta) = 1.5 Q/delta (:func:`lubedyn.lubrication.laws.collision.hertz_force`).
- eqs. (10)-(12), the collision phases: elastic (Hertz) loading; elastic-
  plastic loading beyond first yield (the paper's "yield stress" sigma and
  a force linear in delta, eq. 11); recovery (eq. 12: a Hertz law in
  delta - delta_sigma, a residual indentation).  That is Thornton's (1997,
  J. Appl. Mech. 64, 383) model, implemented as :func:`lubedyn.lubrication.laws.collision.thornton_force` with
  first yield at p0 = 1.6 Y (Johnson 1985, sec. 6.2, nu = 0.3)
  (:func:`lubedyn.lubrication.laws.collision.yield_onset`).
- eq. (17), the film friction coefficient, printed "mu = 3 eta U h e^(alpha
  p)(alpha p - 1) + 1 alpha^2 p^3": Newtonian Barus shear eta0 exp(alpha p)
  U/h integrated over a Hertzian pressure p0 sqrt(1 - r^2/a^2) and divided
  by the load gives mu = 3 eta0 U [e^(alpha p0)(alpha p0 - 1) + 1]/(h alpha^2
  p0^3) (:func:`lubedyn.lubrication.laws.collision.barus_hertz_friction_coefficient`): the printed formula with
  p = p0.
- eqs. (19)-(21), film rupture: the friction coefficient is the fluid value
  weighted by the film's share of the load plus the boundary value mu_b
  weighted by the asperity share (:func:`lubedyn.lubrication.laws.collision.mixed_friction_coefficient`).  The
  paper's fit of the asperity load share against the film parameter
  lambda ("17 e^(-2.84 lambda) + 1.44e-4 (lambda - 2)^1.1 ... 4 lambda^7.8")
  cannot be rebuilt from the extraction; the share is an input here.

The contact and film laws these kinds use are written once in :mod:`lubedyn.lubrication.laws` (Hertz,
Thornton, the squeeze films, the friction laws); the papers' values come from
:mod:`lubedyn.papers`.  Modules: ``base`` (registry types, paper values, lubricant), ``ball_ball``
(the ball-ball film kind), ``ehl`` (the four EHL race kinds), ``rib`` (the rib kind); the registry :data:`KINDS` is here.
"""
from __future__ import annotations

from lubedyn.film_points.ball_ball import (  # noqa: F401  (the package's API: names used by maps, scenes and tests)
    BALL_BALL_AXES, BALL_BALL_OUTPUTS, BALL_BALL_RESOLUTIONS, PRESSURE_NUMBER, RING_GRADING, SQUEEZE_ANGLE,
    approach_speed, ball_ball_default_params, ball_ball_derived, effective_radius, entrainment_number,
    evaluate_ball_ball, field_ball_ball, polar_disk, polar_numbers, polar_speeds, separation_onset_angle,
    solve_ball_ball, squeeze_force_barus, squeeze_number, _ball_ball_setup,
)
from lubedyn.film_points.base import (  # noqa: F401  (the package's API: names used by maps, scenes and tests)
    AxisDef, BALL_DIAMETER, BALL_RADIUS, DENSITY_LAWS, GREASE_ALPHA, INNER_GROOVE_RADIUS, N_BALLS,
    OIL_ALPHA, OIL_ETA0, OIL_RHO0, OUTER_GROOVE_RADIUS, PAPER_B_AXIAL_LOAD, PITCH_DIAMETER_6206, PointKind,
    ROLLER_BASE_OIL_ETA0, ROLLER_BASE_OIL_RHO0, ROLLER_EFFECTIVE_LENGTH, ROLLER_EYRING_STRESS,
    ROLLER_INNER_CONTACT_ANGLE, ROLLER_MEAN_DIAMETER, ROLLER_PITCH_DIAMETER, SHAFT_SPEED_A, SHAFT_SPEED_B,
    VISCOSITY_LAWS,
)
from lubedyn.film_points.ehl import (  # noqa: F401  (the package's API: names used by maps, scenes and tests)
    EHL_BALL_AXES, EHL_OUTPUTS, EHL_REFERENCE_DOMAIN, EHL_RESOLUTIONS, EHL_ROLLER_AXES, EHL_SRR_AXIS,
    SRR_MIN, TRACTION, ehl_ball_inner_race_default_params, ehl_ball_outer_race_default_params,
    ehl_load_response, ehl_roller_race_default_params, evaluate_ehl, field_ehl, _ehl_setup,
    _paper_b_contact_angle, CONTINUATION_PATHS, EHL_LINE_OUTPUTS, EHL_ROLLER_LINE_AXES, ROLLER_RACES,
    ROLLER_SRR_MIN, ehl_roller_cone_default_params, ehl_roller_cup_default_params, evaluate_ehl_line,
    field_ehl_line, roller_race_radius, ROLLER_TRACTION_SHEAR, ROLLER_TRANSITION, ROLLER_TRACTION_NORMALISED,
    transition_slide_to_roll, saturated_transition, normalised_slip, LIGHTER_LOAD_STEP, ROLLER_LINE_LOADS,
    couette_profile, maxwell_traction, roller_grease_params,
)
from lubedyn.film_points.ehl_ball_ball import (  # noqa: F401  (the package's API)
    EHL_BALL_BALL_AXES, EHL_BALL_BALL_OUTPUTS, EHL_BALL_BALL_RESOLUTIONS, ehl_ball_ball_default_params,
    evaluate_ehl_ball_ball,
)
from lubedyn.film_points.rib import (  # noqa: F401  (the package's API: names used by maps, scenes and tests)
    RIB_AXES, RIB_OUTPUTS, RIB_RESOLUTIONS, ehl_rib_default_params, evaluate_ehl_rib, rib_contact, rib_geometry,
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
    "ehl_ball_ball": PointKind(
        name="ehl_ball_ball",
        description=("EHL film between two neighbouring balls of paper B's cage-less 6206 (R = 4.7625 mm each, both "
                     "elastic, E* 113 GPa; Table 1 oil, Roelands matched to alpha 1.85e-8, Dowson-Higginson): "
                     "quasi-steady squeeze and entrainment, load balance; K, C by secants, limiting-shear traction"),
        axes=EHL_BALL_BALL_AXES,
        outputs=EHL_BALL_BALL_OUTPUTS,
        evaluate=evaluate_ehl_ball_ball,
        default_params=ehl_ball_ball_default_params,
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
    "ehl_roller_cone": PointKind(
        name="ehl_roller_cone",
        description=("EHL line contact of paper A's tapered roller with the cone (inner race), per metre of "
                     "contact: R_x 9.395 mm from the model's geometry, base oil 0.1 Pa s (assumed) with the "
                     "grease's alpha, Eyring flow tau0 5 MPa, film-scaled domain, limiting-shear traction"),
        axes=EHL_ROLLER_LINE_AXES,
        outputs=EHL_LINE_OUTPUTS,
        evaluate=evaluate_ehl_line,
        default_params=ehl_roller_cone_default_params,
        field=field_ehl_line,
        signed=("Traction coefficient [-]",),
        sheared={"Traction coefficient [-]": ROLLER_TRACTION_SHEAR},
    ),
    "ehl_rib": PointKind(
        name="ehl_rib",
        description=("EHL point contact of paper A's roller end (sphere r_s 136.2 mm) on the cone's rib: R_x 169.0 mm "
                     "(circumferential, entrainment), R_y 136.2 mm, base oil 0.1 Pa s (assumed) or a Table 2 grease "
                     "(Herschel-Bulkley flow), Barus alpha 4.662e-8, per flange load and entrainment speed"),
        axes=RIB_AXES,
        outputs=RIB_OUTPUTS,
        evaluate=evaluate_ehl_rib,
        default_params=ehl_rib_default_params,
    ),
    "ehl_roller_cup": PointKind(
        name="ehl_roller_cup",
        description=("EHL line contact of paper A's tapered roller with the cup (outer race), per metre of "
                     "contact: R_x 11.906 mm from the model's geometry (concave race), otherwise as "
                     "ehl_roller_cone"),
        axes=EHL_ROLLER_LINE_AXES,
        outputs=EHL_LINE_OUTPUTS,
        evaluate=evaluate_ehl_line,
        default_params=ehl_roller_cup_default_params,
        field=field_ehl_line,
        signed=("Traction coefficient [-]",),
        sheared={"Traction coefficient [-]": ROLLER_TRACTION_SHEAR},
    ),
}
