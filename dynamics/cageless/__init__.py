r"""Cage-less deep-groove ball bearing (paper B: 6206 size, 14 balls, local
functional slots, balls colliding through the oil film), as a numba
right-hand side.

Frames and bodies
-----------------
Inertial frame: x horizontal, y up (gravity -g e_y), z the bearing axis.  The
outer ring is fixed with its centre at the origin.  The inner ring (carrying
the rotor's mass) translates freely (x, y; and z with the 6-DOF balls) and
turns about z (angle theta, speed omega); the rotor turns at Omega.  Ball j
has centre c_j, velocity v_j and angular velocity w_j.

Degrees of freedom (option ``dof``)
    ``"6dof"``: per ball position (3), unit quaternion (4, scalar first, body
    -> inertial, :mod:`lubedyn.dynamics.rotations`), velocity (3) and body-frame
    angular velocity (3) with Euler's equations (the gyroscopic term
    w x J w vanishes for a sphere but is kept general).  13 states/ball.
    ``"planar"``: the ball stays in the mid-plane z = 0: orbital angle phi,
    radial position r, spin angle and spin speed about the axis-parallel
    direction, (phi, r, theta_b, dphi/dt, dr/dt, omega_b), with
    m (r'' - r phi'^2) = F_r, m (r phi'' + 2 r' phi') = F_t, J omega_b' = T_z.
    6 states/ball.  No axial load (it needs a contact angle).

State vector (:meth:`CagelessBearing.state_layout` names every entry)::

    [ring x, y, z, theta, vx, vy, vz, omega, rotor Omega] (9)
    [delta_max of ball pair j, j+1 (mod Z)]               (Z: plastic memory)
    [ball 0 block, ball 1 block, ...]                      (Z x 13 or Z x 6)

Ball-race contact (rigid rings, groove curvature centres)
---------------------------------------------------------
The groove of a race is a torus; its curvature centre circle has radius
R_oc = D_o/2 - r_o (outer, about the origin) and R_ic = D_i/2 + r_i (inner,
about the inner-ring centre c_i, axial offset z_i).  For a ball at radial
distance rho from the race axis in its own radial plane (unit e_r), with u =
c - (race centre + R_gc e_r) and L = |u|::

    delta = L - (r_g - D/2),   n = u/L,   Q = K delta^1.5 (1 + alpha d(delta)/dt)  (Hunt-Crossley)

the force on the ball is -Q n at the contact point p = c + (D/2) n (the
reaction +Q n acts on the inner ring); the contact angle reported is the
angle of the load line, atan(n_z/n_r) at the outer race and atan(-n_z/n_r)
at the inner race (equal for a ball loaded only by the two races).
K is the exact Hertz constant of :mod:`lubedyn.dynamics.contacts` at the zero-angle
curvature (its change with the angle through gamma is < 0.1 %).  Traction:
the closed-form curve mu(SRR) of :func:`lubedyn.lubrication.laws.traction.traction_coefficient`
against the tangential sliding velocity v_s = (v + w x (D/2) n) - v_race(p);
entrainment u_e = |((v_ball + v_race)/2 - v_p)_t| with v_p the velocity of the
contact point (it moves with the ball's orbit).  Spin and rolling-resistance
moments are not modelled.

Functional slots (paper B, Table 4: width W = 3.5 mm across the groove, length L_s = 11.5 mm along it, depth 1 mm; EDM-cut in the raceway)
    The groove surface is missing where the contact point lies within
    |s| < L_s/2 (arc length along the race from the slot centre) and |z_p| <
    W/2 (axial, from the groove centre plane): the groove force is multiplied
    by 1 - w_s(s) w_z(z_p) (smooth steps of width ``slot_blend``).  Over the
    slot a ball that has lost its groove support drops onto the slot's two
    edges (circles at z = +-W/2 on the groove surface; a sphere against an
    edge rounded with ``slot_edge_radius``, Hertz, weighted by w_s).  A ball
    of D = 9.525 mm dips R - sqrt(R^2 - W^2/4) = 0.33 mm into a 3.5 mm slot,
    less than its 1 mm depth, so the slot floor is never reached (checked).
    Default: one slot in the outer (fixed) ring at the bottom of the load
    zone (azimuth 270 deg, under the radial load), as the paper's figure 3
    discussion places it ("the bearing area has the lowest set of functional
    slots"); count, azimuths and race are options (an inner-ring slot turns
    with theta).

Ball-ball contact between neighbours j, j+1 (no cage; the train keeps its
order since Z D < pi d_m): the film + Hertz series law with collision phases
and film-rupture friction of :func:`lubedyn.dynamics.contacts.ball_ball_normal`.

Inner ring and rotor (option ``scenario``)
    ``"steady"``: omega fixed (driven inner ring), Omega unused.
    ``"drop"``: the rotor, spinning at Omega_0, has landed on the inner ring
    (at rest with the balls, in the quasi-static equilibrium under F_r, F_a)
    and drags it by friction at the rotor-inner ring contact::

        T_f = mu_r F_r r_c tanh((Omega - omega)/omega_reg)
        J_ring omega' = T_balls + T_f,   J_rotor Omega' = -T_f   (J_rotor = inf: driven rotor)

    (a regularised Coulomb law; F_r the normal load in the rotor-ring
    contact, r_c the bore radius).  An initial downward ring speed
    ``drop_speed`` models the impact.
    ``"free"``: omega free, no rotor (T_f = 0).

The inner-ring assembly (ring + rotor, mass ``ring_mass``) carries the radial
load F_r downward (-y) including its own weight, i.e. the applied force is
F_r - m g plus gravity m g, and the axial load F_a along +z.  Gravity also acts
on the balls.

API
---
:class:`CagelessBearing` (parameters, ``args()`` the kernels' :class:`KernelArgs`,
``initial_state()`` the quasi-static start, ``state_layout()``/``state_names()``,
``omega_max()`` for the explicit step limit); :func:`rhs` (integrator
contract ``rhs(t, y, args, dydt)``); :func:`forces` / :func:`forces_many`
(contact loads, angles, slip, ball-ball force vectors, film thickness and
collision phase at sampled states, columns :data:`DIAG_NAMES`);
:func:`bearing_energy`, :func:`angular_momentum_z` (invariants for checks).

Speed
-----
The contact kernels take and return scalars and are inlined (numba
``inline='always'``), ball kinematics and the quaternion algebra are written
out on scalars (no array views in the ball loops: each costs an atomic
reference-count pair), the contact angle is computed only for
:func:`forces`, and points far from a slot are skipped by a dot product
before the atan2.  Measured costs per ``rhs`` call are in
``benchmarks/README.md`` ("Cost of the bearing right-hand side").
A model without a film map or traction maps passes None in their places of
:meth:`CagelessBearing.args`, so numba prunes the map readers by type: the
rhs call at the start of the drop then takes 2.46 us against 4.42 us with
the unused readers compiled in (same process, fastest of 300 x 100 calls;
the 5 ms drop with DOPRI5 0.099 s against 0.203 s, identical steps and
states), and the cold compile of the main job's kernels falls by ~40 % CPU.
Largest stable RK4 step at 10,000 rpm (F_r 2000 N, F_a 200 N, slot): 1.33e-5
s steady, 1.25e-5 s during the rotor drop with ball collisions;
:meth:`CagelessBearing.omega_max` gives 2.83/omega_max = 1.03e-5 s
(conservative by ~25 %).

Modules: ``layout`` (state layout, option codes, parameter and diagnostic indices), ``kernels`` (the
compiled right-hand side, :func:`rhs`, :func:`forces`), ``model`` (:class:`CagelessBearing`),
``invariants`` (energy, angular momentum).  Every name is re-exported here.
"""
from __future__ import annotations

from .invariants import (  # noqa: F401  (the package's API)
    angular_momentum_z, bearing_energy,
)
from .kernels import (  # noqa: F401  (the package's API)
    _ball_races, _evaluate, _race_contact, _rotate3, _slot_directions, _slot_weight, _smooth_in,
    _traction_from_map, forces, forces_many, rhs,
)
from .layout import (  # noqa: F401  (the package's API)
    DIAG_NAMES, DOFS, D_AI, D_AO, D_BBN, D_BBT, D_BBX, D_BBY, D_BBZ, D_GAP, D_H, D_PHASE,
    D_PSI, D_PSIDOT, D_QE, D_QI, D_QO, D_SPIN, D_SRRI, D_SRRO, D_VSI, D_VSO, MAP_SPEED_AXES, NB_6DOF, NB_PLANAR,
    N_DIAG, N_RING, N_RING_DIAG, OPTIONS, PARAMETERS, PARAMETER_DTYPE, RACES, RACE_FILMS, RING_DIAG_NAMES,
    SCENARIOS, TRACTIONS, TRACTION_MAP_BELOW_AXIS, BallBallMap, KernelArgs, MapArrays, TractionMaps,
    parameter_record,
)
from .groups import Bearing, Fidelity, Films, Initial, Operating, Slots  # noqa: F401  (the package's API)
from .model import (  # noqa: F401  (the package's API)
    CagelessBearing, _map_arrays, _traction_arrays,
)
