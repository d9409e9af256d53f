r"""Isothermal elastohydrodynamic (EHL) point and line contacts.

Equations (SI, gauge pressure p, x the entrainment direction)::

    div(rho h^3/(12 eta) grad p) = div(rho h u_m) + rho dh00/dt      (Reynolds)
    h(x) = h00 + x^2/(2 R_x) + y^2/(2 R_y) + u(x)                   (film)
    u(x) = 1/(pi E*) int p(x')/|x - x'| dA'                         (elasticity)
    int p dA = W                                                    (load balance)
    p >= 0, R(p) >= 0, p R(p) = 0                                   (outlet cavitation)

u_m = (u_1 + u_2)/2 along +x, eta(p) and rho(p) from :mod:`lubedyn.lubrication.laws.lubricant`.
Line contacts drop y (loads per unit length, the strip kernel of
:mod:`lubedyn.lubrication.elastic`).

Discretisation
--------------
P1 finite elements (scikit-fem) on a uniform tensor grid whose nodes are the
cell centres of the FFT deflection grid (pressure constant on each node's dual
cell).  The Reynolds residual is the Galerkin form of
:mod:`lubedyn.lubrication.reynolds` plus SUPG stabilisation of the transport term::

    + int tau (u_m . grad v) (u_m . grad(rho h) + rho dh00/dt)
    tau = l/(2|u_m|) (coth Pe - 1/Pe),  Pe = |u_m| l rho h/(2 k),  k = rho h^3/(12 eta)

(l the cell length along x).  tau vanishes where the film is Poiseuille
dominated (inlet, light loads) and tends to full upwinding in the contact,
where k -> 0 and the Galerkin transport alone would oscillate.

Reynolds-Eyring flow (``Lubricant(eyring_stress=tau0)``): k becomes
k Phi(x), x = h |grad p|/(2 tau0), Phi = 3 (x cosh x - sinh x)/x^3 (the
Poiseuille flow of the sinh law in pure rolling,
:func:`lubedyn.lubrication.laws.lubricant.eyring_flow_factor`); the flux then depends on
grad p nonlinearly, and the Jacobian carries its tensor part
k Phi'/x (h/(2 tau0))^2 grad p grad p^T, dPhi/dh, and the SUPG parameter's
dependence on grad p (Pe ~ 1/Phi).  The pressure still does not depend on
sliding (pure-rolling flow factor), so a map's traction axis stays
post-processing.

Herschel-Bulkley (grease) flow (``Lubricant(herschel_bulkley=HerschelBulkleyFlow(tau_y, n, creep))``,
the viscosity law then being the consistency phi(p) = phi0 exp(alpha p) [Pa s^n]): k becomes
k Phi_HB(T_w, phi), T_w = h |grad p|/2, Phi_HB = 3 (T_w/phi)^(m-1) F(tau_y/T_w), m = 1/n,
F(xi) = (1 - xi)^(m+1) [(1 - xi)/(m+2) + xi/(m+1)] (0 where T_w <= tau_y: a plug across the film),
the slit flow of the Herschel-Bulkley law derived in :mod:`lubedyn.lubrication.laws.lubricant`
(Buckingham-Reiner for n = 1), plus an optional creep eps (default 0).  The Jacobian has the same
tensor and SUPG terms as Eyring flow and, since k ~ phi^(-1/n), dk/dp = ... (1/n) phi'/phi.  Same
pure-rolling superposition as Eyring (Couette rho h u_m + the pressure flow).  Line contacts use
Fischer-Burmeister (the active set kept cycling with plugs at the cavitation boundary), and with no
``initial`` the solve starts from the Newtonian contact with the apparent viscosity tau_y/D +
phi0 D^(n-1) at D = u_m/h_c (then 0.5, 0.25, 0.125 times it; :func:`lubedyn.lubrication.ehl.solve._solve_hb`);
the Hertz start stalls.  Measured on paper A's cone (R 9.395 mm, E' 225 GPa, 30 C, 257 nodes on
[-20, 3] b): calcium converges over 50-135 kN/m x 10-20 m/s, polyurea on 5 of 7 points (not
135 kN/m, 20 m/s nor 50 kN/m, 20 m/s: there the Newtonian starts fail), lithium (n = 0.31) on all 7
through a homotopy: where the Herschel-Bulkley iteration from a converged Newtonian start stalls (as
lithium's does everywhere), the grease is reached along yield stress s tau_y and exponent 1 - s (1 - n),
s: 0 -> 1, with the consistency that keeps the apparent viscosity of the start
(:func:`lubedyn.lubrication.ehl.solve._hb_homotopy`; 6-11 steps, 11-26 s a point, h_c 39-76 nm, 1.14-1.39
times the Newtonian start's); the same holds on paper A's rib (point contact, 500 N, 11.3 m/s: 0.240 um);
calcium at 135 kN/m, 10 m/s has two discrete solutions (h_min 5.7 % apart) as the Newtonian roller
does (tests/test_ehl_hbflow.py).  Reported M and L read phi0 as Pa s.

Assembly is vectorised on the uniform grid (:mod:`lubedyn.lubrication.ehl.assembly`:
one template product and one scatter per matrix; equal to scikit-fem's
``asm`` of the same forms to round-off, :meth:`_Problem.assemble_skfem`).

Graded line grids (``EHLGrid(refine=r > 1, refine_zone, refine_width)``, line contacts only): the
nodes are equidistant in a smooth node density, r times denser on the zone (``EHLGrid.x_nodes``;
the coarser levels of the grid sequence are every second node).  The deflection is then the dense
influence matrix of the nodes' own cells (:func:`lubedyn.lubrication.elastic.line_influence_matrix`, the
Toeplitz kernel on a uniform grid), the assembly takes one template per element
(``assembly.ElementForms``) and SUPG the element's own length.  Measured (tests/test_ehl_graded.py,
benchmarks/ehl_graded.py): on Moes M = 20, L = 10 the outlet spike of graded 257 nodes (refine 4 on
[-1.2, 1.2] b) is as high as on uniform 513-1025 nodes (p_max 1.43-1.53 p_Hertz against 1.00 / 1.52 /
1.67 on uniform 257 / 513 / 1025) at a fiftieth of 1025's time; h_c moves by 0.1 % (the longer inlet
cells).  Where it stops: in the hydrodynamic-to-EHL knee of paper A's roller (L = 53, M = 0.4-0.8)
the Newton iteration on a graded 257-node grid fails at 14 of 38 loads of a 3 %-step load
continuation (full steps of 1-6 p_Hertz from the converged neighbour, the cavitated set moving),
as it does on uniform 1025 nodes: the finer the spike is resolved, the harder the iteration.

Pseudo-transient continuation (``EHLOptions(pseudo_transient=dtau0)``, the active-set Newton): the
Jacobian gains the lumped transient term of d(rho h)/dt with a pseudo time step that grows as the
residual falls (switched evolution relaxation), so the step is damped along the near-null mode of the
Couette-dominated zone and the iteration ends as plain Newton (:func:`newton._pseudo_transient`).  With
it and a compressible (Dowson-Higginson) film, paper A's roller contacts converge on the graded grid over
the whole map range (0.7-300 kN/m, 7-28 m/s), and the roller maps are built so (cases/maps/README.md).

Coupled solver
--------------
Newton on (p, h00): J = A + D K with A = dR/dp at fixed h (sparse), D = dR/dh
(sparse) and K the elastic influence operator (FFT).  The Jacobian is exact
for the discretisation it solves: besides k(p, h), rho(p) and the recovered
flux, the SUPG parameter is differentiated, tau'(Pe) = l/(2 u_m) (1/Pe^2 -
1/sinh^2 Pe) with Pe = 6 u_m l eta/h^2, so d tau/dp = tau'(Pe) Pe eta'/eta
and d tau/dh = -2 tau'(Pe) Pe/h (the alternative, tau frozen per grid level,
would change the discrete solution; differentiating keeps it: converged H_c
unchanged to 1e-14).  Checked against finite differences of the residual in
tests/test_ehl_point.py; the last Newton steps converge quadratically.
(Measured effect: small; the consistent strong residual multiplying
d tau vanishes at the solution, so before the fix the iteration histories
were the same to three digits.)  The load equation is bordered: dense
systems solve J z1 = -R and J z2 = -dR/dh00 with one LU, then
dh00 = -(w.z1 + w.p - W)/(w.z2) and dp = z1 + dh00 z2 (w_i = int phi_i dA);
iterative ones run one GMRES on the bordered system (:meth:`_FBLinear.solve_bordered`).  Two treatments of the outlet
cavitation (``EHLOptions.method``; ``auto``: the first for points, the
second for lines):

- ``fischer_burmeister`` (:func:`_fb_newton`): semismooth Newton on
  phi(p_i/p_ref, s_i R_i) = 0, phi(a, b) = sqrt(a^2 + b^2) - a - b, which is
  the complementarity itself (no active set), with an Armijo line search on
  |phi|^2 + (load error)^2.  Linear systems: dense LU up to
  ``dense_max`` unknowns, else restarted GMRES with FFT products,
  right-preconditioned by the sparse LU (``splu``, minimum-degree ordering of
  A^T + A) of the same matrix with K truncated to a (2s+1)^2 stencil; the
  factorisation is kept while GMRES needs fewer than ``precond_refresh``
  iterations, and GMRES stops at rtol min(``gmres_forcing``, |phi|)
  (inexact Newton; 1e-3: a looser 0.1 saved 10 % at 129 x 129 but let the
  257 x 257 iteration wander).
- ``active_set`` (:func:`_active_set_newton`): nodes whose update would go
  negative join the cavitated set (p = 0), cavitated nodes whose multiplier
  R_i turns negative leave it; dense LU or ILU-GMRES.

Each step is capped so that no pressure changes by more than ``max_step``
p_ref (p_Hertz, or the largest pressure where that is smaller).

Start and grid sequence: Hertz pressure and a closed-form central film
(:func:`_film_guess`), the first-order SUPG solution as a defect-correction
start for the second-order scheme, and nested iteration (coarse solution
prolonged to the next grid).  Points run the first-order start on the
coarsest (33 x 33) grid only, then second order on every grid; if the
second-order iteration from the prolonged start fails, the full chain with
first-order starts on every grid is run (measured need: M = 20, L = 10 on
129 x 129); the second-order attempt from the prolonged start gives up after
``max_damped`` damped steps (on 257 x 257 every step is damped: the outlet
spike's nodes ask for steps of several p_Hertz).  Lines run the first-order
start on every grid; if the second-order iteration from it fails, second
order from the prolonged coarse second-order solution is tried (measured
need: M = 20, L = 10 on 1025 nodes).  A coarse level that does not converge
in ``coarse_max_iter`` steps hands its last iterate on (it is only a start).
Where a coarse level fails outright (a heavily loaded contact it does not
resolve: the active-set iteration stalls, its Jacobian turns singular), the
requested grid is solved once more from the Hertz start, without the nested
levels (measured: Dowson-Higginson M = 500, L = 5 and Barus M = 2000, L = 5
line contacts, whose 257- or 129-node levels fail, converge so on 513 and 1025
nodes); if that fails too, the error names the level that failed and the grid
asked for.
Starts (coarse levels, first-order stages) are converged only to
``coarse_rtol`` (1e-3 of p_Hertz: the next grid changes the pressure by
0.2 - 0.5 p_Hertz at the spike), the final stage to ``rtol``.

Convergence test, on the full (undamped) Newton step before any line
search: max|dp| <= rtol p_ref, |dh00| <= rtol b^2/R_x and, after that step,
|int p dA - W| <= 10 rtol W (active set: and no cavitated node whose scaled
multiplier is below -rtol p_ref, :func:`_largest_negative_multiplier`).
The step is then taken and the iteration stops.  An earlier test asked for
an undamped step (omega = 1) as well; at the round-off floor the line
search's residual or merit is noise, omega was halved at random and a solve
at |dp| = 1e-15 p_Hertz ran out of iterations on one machine and not on
another (tests/test_roundoff.py perturbs every residual by 1 - 100
round-off units and requires the same state).  Otherwise, after ``max_iter`` steps or ``max_stalls`` stalled
line searches, :class:`~lubedyn.lubrication.errors.ConvergenceError` naming M and L.
A converged state satisfies the discrete complementarity (tests/test_ehl.py
checks it in the scikit-fem reference assembly).  Limit, measured on paper
A's roller (Barus, alpha p_Hertz = 44, L = 56): across the Hertz zone the
Poiseuille term is 1e-15 ... 1e-36 of the Couette term, below round-off, so
the discrete Reynolds equation there is rho h = const to machine precision
and several states satisfy the discrete problem (10 kN, 8.84 m/s, 257 nodes:
two starts give spikes 0.18 b apart, h_min 5 % apart, both with free-node
residual 2.5e-11 and cavitated multipliers >= 0).  No convergence test can
pick one; at alpha p_Hertz = 33 both starts agree to 1e-15.  Capping the
viscosity at 1e6 ... 1e12 Pa s or a Dowson-Higginson density leaves the two
states; Eyring flow (tau0 = 5 MPa) removes them: five starts agree to 1e-13
(tests/test_ehl_eyring.py pins both).  With Eyring flow the Newton iteration
is less robust: some starts fail (0.944 times the load at 10 kN; from the
Newtonian state at 15 kN), and on 1025 nodes no start converged at 10 kN,
8.84 m/s (the outlet's x grows with refinement: 56 on 257 nodes, 90 on 513).
An ``initial`` from another grid is interpolated onto this one
(:func:`_prolong`).

Reach (circular, L = 10; benchmarks/ehl.py times it, benchmarks/method_limits.py
sweeps M and the grid): M = 20 ... 200 converge on 33 x 33, M = 20 ... 500 on
65 x 65, M = 20 ... 1000 on 129 x 129 (M = 20, 50 and 1000 through the fallback
chain) in 6 - 13 Newton steps; M = 100 converges on 257 x 257, but slowly, because
each Newton step there needs a sparse LU of the preconditioner and GMRES on
66,000 unknowns and the outlet spike needs a global Newton phase on every
level.  M = 200 on 257 x 257 fails clearly after both starts; M = 500 on
33 x 33 and M = 1000 on 33 and 65 fail clearly (the film reaches the floor:
outlet constriction not resolved).

Multigrid (``EHLOptions(method="multigrid")``, point contacts only)
-------------------------------------------------------------------
:mod:`lubedyn.lubrication.ehl.multigrid`: the FAS multigrid of Venner & Lubrecht
(finite differences on the same nodes, second-order upstream wedge, mixed
Gauss-Seidel / Jacobi-distributive line relaxation with projection P >= 0,
H00 on the coarsest grid, FFT deflection on every level, FMG start and
W-cycles), routed by :func:`solve_ehl` to :func:`_solve_multigrid`, which
returns the same :class:`EHLSolution` (film, pressure, friction, VTK) on
the :class:`_Problem` nodes.  Grids nx = 16 2^k + 1 (17 ... 1025; ny chosen
by :func:`multigrid_grid`); ``max_point_grid`` does not apply.  Steady
contacts with a load or an approach; no squeeze, no line contacts.
Reach (circular, L = 10; benchmarks/ehl.py times it): 257 x 257 and 513 x 513
for M = 20 ... 1000 in 11-12 W(3,1)-cycles to a relative residual of 1e-5, in
seconds where the FEM Newton needs minutes; M = 1000
converges from 129 x 129 on (on 65 x 65 the film goes negative: clear
ConvergenceError), M = 2000 from 257, M = 3000 on 513 (stagnation error on
129 and 257).  H_c converges at second order to the same limit as the FEM
Newton (M = 100: Richardson 4.648 from both), but the finite-difference
scheme is less accurate per grid (M = 100: -3.7 % on 129 x 129 against the
FEM's -0.3 %), so in error against CPU time (benchmarks/ehl.py) the two are about even at light
loads; the multigrid is ahead at M = 1000, converges where the Newton
methods do not (M = 200 on 257 x 257, 513 x 513) and solves 257 x 257 in
seconds.  The default stays the FEM Newton (``auto``): it also gives squeeze
films and the linearised normal coefficients, and it is the method the
coupling code is validated with.  Limit, measured on paper B's most loaded
ball / inner race contact (k = 11, M = 1001, L = 25.4,
cases/ehl_ball_inner_race.toml): it converges on 65 x 33 (y_max = 1.5 b_y;
h_c 1.041 um against the FEM's 1.120 um on the same grid) and on 129 x 713
isotropic cells (1.104 um), but stagnates on 129 x 33 and 257 x 1425 and
diverges on 513 x 2849 (clear errors; pinned in tests/test_cli.py): the
Jacobi-distributive rows and the bilinear transfers assume hx = hy, so
elongated, heavily loaded contacts stay with the FEM Newton.

Stop reasons, a-posteriori checks, work budget
----------------------------------------------
Every solution's ``info`` carries ``stop_reason`` ("tolerance met") and
``stop_detail`` (the figures of the test that ended it: the full Newton step,
load error and multipliers, or the multigrid's error/residual stop); every
:class:`~lubedyn.lubrication.errors.ConvergenceError` carries ``.stop`` (``reason``:
iteration limit, line search stalled, damped-step budget, singular Jacobian,
non-finite pressure, film collapsed, work budget, a-posteriori check failed,
or the multigrid's diverged/stagnated).  The active-set error's hint is computed
from the state (the test that refused a converged step, cavitated-set changes,
the film floor, a finer grid only where M exceeds what the grid resolves).
Hints name what a case file can set ([grid] nx, ny; [solver] method,
max_step, max_iter) and, from Python, the EHLOptions field; where Moes' M is
the cause (a very heavily loaded or slow contact), they say so and name the
grid or method measured to converge there; an error on a coarser level of the
nested start names that level and the grid asked for.
A converged solution can still be wrong where the grid does not resolve the
contact (measured: line M = 1000, L = 10 on 257 nodes, +86 % off Moes, +49 %
with a Dowson-Higginson density; multigrid M = 1000 on 129 x 129, -35 %):
:func:`check_solution` compares it with the closed form (Barus, incompressible,
Newtonian) and, for every density, viscosity and flow law, with the same
contact on the one-level-coarser grid (the nested or FMG start's level, or
solved from the solution by :func:`lubedyn.lubrication.ehl.solve._resolution_levels`),
and, where the coarser level cannot tell (it collapsed, differs by more than
5 %, or the inlet's piezoviscous rise spans fewer than 6 cells), with the
one-level-finer grid; it warns (``EHLOptions(strict=True)``: raises),
naming the figures and the grid needed (point contacts: the finer grid only up
to 4500 nodes, 33 x 33 -> 65 x 65; above, the coarser level's estimate where
that level has 8 cells across the Hertz contact).
Cost: a line contact's coarser and finer levels each cost less than its solve;
a point contact's nested level is reused where it converged, and its finer level
(33 x 33 -> 65 x 65 only) costs seconds (benchmarks/method_limits.py records each
solve's time with its checks).
``EHLOptions(check_resolution=False)`` skips these solves (the closed form and
the inlet are still checked).
``EHLOptions.max_work`` bounds the Newton steps of one :func:`solve_ehl`
call, every start and fallback included (default :data:`DEFAULT_MAX_WORK`:
100 for points, 400 for lines, about 2.5 times the most a converging contact of
the EHL limit sweeps needs; :mod:`lubedyn.lubrication.ehl.budget`).

Normal film coefficients: :func:`ehl_normal_coefficients`.

References: Venner & Lubrecht, *Multilevel Methods in Lubrication*, Elsevier
2000 (dimensionless groups, domain, test cases); Habchi et al., Tribol. Int. 41
(2008) 1163 (full-system FEM EHL, SUPG); Liu, Wang & Liu, Wear 243 (2000) 101
(DC-FFT).

Modules
-------
=================  ============================================================
``contact``        EHLContact (geometry, materials, lubricant, speeds, load),
                   Traction laws, SUPG parameter
``options``        EHLGrid, EHLOptions, method names
``problem``        _Problem: Reynolds forms, elastic deflection, load balance
``assembly``       vectorised assembly on the uniform grid (and per element on graded line grids)
``newton``         active-set and Fischer-Burmeister Newton solvers
``multigrid``      FAS multigrid point-contact solver (Venner & Lubrecht)
``solve``          solve_ehl: grid sequence, method choice, multigrid driver
``budget``         work budget of a solve
``checks``         closed-form comparison and a-posteriori (resolution) checks
``solution``       EHLSolution
``coefficients``   film stiffness and damping (ehl_normal_coefficients)
=================  ============================================================
"""
from .checks import (COARSE_TOLERANCE, FORMULA_ENVELOPE, FORMULA_TOLERANCE, check_solution,
                     closed_form_central_film)
from .coefficients import NormalCoefficients, ehl_normal_coefficients
from .contact import TRACTION_MODELS, EHLContact, Traction, supg_parameter
from .options import EHL_METHODS, FIRST_ORDER_STARTS, EHLGrid, EHLOptions
from .solution import EHLSolution
from .solve import multigrid_grid, solve_ehl

__all__ = [
    "COARSE_TOLERANCE", "EHL_METHODS", "FIRST_ORDER_STARTS", "FORMULA_ENVELOPE", "FORMULA_TOLERANCE", "TRACTION_MODELS",
    "EHLContact", "EHLGrid", "EHLOptions", "EHLSolution", "NormalCoefficients", "Traction", "check_solution",
    "closed_form_central_film", "ehl_normal_coefficients", "multigrid_grid", "solve_ehl", "supg_parameter",
]
