r"""Isothermal elastohydrodynamic (EHL) point and line contacts.

Equations (SI, gauge pressure p, x the entrainment direction)::

    div(rho h^3/(12 eta) grad p) = div(rho h u_m) + rho dh00/dt      (Reynolds)
    h(x) = h00 + x^2/(2 R_x) + y^2/(2 R_y) + u(x)                   (film)
    u(x) = 1/(pi E*) int p(x')/|x - x'| dA'                         (elasticity)
    int p dA = W                                                    (load balance)
    p >= 0, R(p) >= 0, p R(p) = 0                                   (outlet cavitation)

u_m = (u_1 + u_2)/2 along +x, eta(p) and rho(p) from :mod:`lubrication.laws.lubricant`.
Line contacts drop y (loads per unit length, the strip kernel of
:mod:`lubrication.elastic`).

Discretisation
--------------
P1 finite elements (scikit-fem) on a uniform tensor grid whose nodes are the
cell centres of the FFT deflection grid (pressure constant on each node's dual
cell).  The Reynolds residual is the Galerkin form of
:mod:`lubrication.reynolds` plus SUPG stabilisation of the transport term::

    + int tau (u_m . grad v) (u_m . grad(rho h) + rho dh00/dt)
    tau = l/(2|u_m|) (coth Pe - 1/Pe),  Pe = |u_m| l rho h/(2 k),  k = rho h^3/(12 eta)

(l the cell length along x).  tau vanishes where the film is Poiseuille
dominated (inlet, light loads) and tends to full upwinding in the contact,
where k -> 0 and the Galerkin transport alone would oscillate.

Reynolds-Eyring flow (``Lubricant(eyring_stress=tau0)``): k becomes
k Phi(x), x = h |grad p|/(2 tau0), Phi = 3 (x cosh x - sinh x)/x^3 (the
Poiseuille flow of the sinh law in pure rolling,
:func:`lubrication.laws.lubricant.eyring_flow_factor`); the flux then depends on
grad p nonlinearly, and the Jacobian carries its tensor part
k Phi'/x (h/(2 tau0))^2 grad p grad p^T, dPhi/dh, and the SUPG parameter's
dependence on grad p (Pe ~ 1/Phi).  The pressure still does not depend on
sliding (pure-rolling flow factor), so a map's traction axis stays
post-processing.

Assembly is vectorised on the uniform grid (:mod:`lubrication.ehl_assembly`:
one template product and one scatter per matrix; equal to scikit-fem's
``asm`` of the same forms to round-off, :meth:`_Problem.assemble_skfem`).

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
line searches, :class:`~lubrication.errors.ConvergenceError` naming M and L.
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

Measured (circular, L = 10, benchmarks/ehl.py and benchmarks/README.md;
CPU seconds of one core, the shared machine's wall times were 3-8 times
more): M = 20 ... 200 converge on 33 x 33 (6 steps, 0.6 - 0.9 s); M = 20 ...
500 on 65 x 65 (9 - 11 steps, 1.2 - 1.8 s); M = 20 ... 1000 on 129 x 129 (7 -
13 steps, 8 - 31 s; M = 20, 50 and 1000 through the fallback chain; 1.6 - 3.7
times less CPU than before these changes); M = 100 on 257 x 257 in 136 s
(first-order chain, 16 second-order steps; before: 661 s wall): far from a
10 s target, because each Newton step there costs about 5 s (sparse LU of
the preconditioner 2.7 s, GMRES 2 s) and the outlet spike needs a global
Newton phase on every level.  M = 200 on 257 x 257 fails clearly after
both starts (247 s).  M = 500 on 33 x 33 and M = 1000 on 33 and 65 fail
clearly (the film reaches the floor: outlet constriction not resolved).

Multigrid (``EHLOptions(method="multigrid")``, point contacts only)
-------------------------------------------------------------------
:mod:`lubrication.ehl_multigrid`: the FAS multigrid of Venner & Lubrecht
(finite differences on the same nodes, second-order upstream wedge, mixed
Gauss-Seidel / Jacobi-distributive line relaxation with projection P >= 0,
H00 on the coarsest grid, FFT deflection on every level, FMG start and
W-cycles), routed by :func:`solve_ehl` to :func:`_solve_multigrid`, which
returns the same :class:`EHLSolution` (film, pressure, friction, VTK) on
the :class:`_Problem` nodes.  Grids nx = 16 2^k + 1 (17 ... 1025; ny chosen
by :func:`multigrid_grid`); ``max_point_grid`` does not apply.  Steady
contacts with a load or an approach; no squeeze, no line contacts.
Measured (circular, L = 10, CPU s of one core, benchmarks/ehl.py and
benchmarks/README.md): 257 x 257 in 2.0-2.6 s for M = 20 ... 1000 (11-12
W(3,1)-cycles to a relative residual of 1e-5), 513 x 513 in 7-14 s; M = 1000
converges from 129 x 129 on (on 65 x 65 the film goes negative: clear
ConvergenceError), M = 2000 from 257, M = 3000 on 513 (stagnation error on
129 and 257).  H_c converges at second order to the same limit as the FEM
Newton (M = 100: Richardson 4.648 from both), but the finite-difference
scheme is less accurate per grid (M = 100: -3.7 % on 129 x 129 against the
FEM's -0.3 %), so in error against CPU time the two are about even at light
loads; the multigrid is ahead at M = 1000, converges where the Newton
methods do not (M = 200 on 257 x 257, 513 x 513) and meets the 257 x 257
speed target.  The default stays the FEM Newton (``auto``): it also gives squeeze
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
:class:`~lubrication.errors.ConvergenceError` carries ``.stop`` (``reason``:
iteration limit, line search stalled, damped-step budget, singular Jacobian,
non-finite pressure, film collapsed, work budget, a-posteriori check failed,
or the multigrid's diverged/stagnated).  The active-set error's hint is computed
from the state (the test that refused a converged step, cavitated-set changes,
the film floor, a finer grid only where M exceeds what the grid resolves).
A converged solution can still be wrong where the grid does not resolve the
outlet constriction (measured: line M = 1000, L = 10 on 257 nodes, +86 % off
Moes; multigrid M = 1000 on 129 x 129, -35 %): :func:`check_solution`
compares it with the closed form and with the one-level-coarser solution and
warns (``EHLOptions(strict=True)``: raises), naming the grid needed.
``EHLOptions.max_work`` bounds the Newton steps of one :func:`solve_ehl`
call, every start and fallback included (default :data:`DEFAULT_MAX_WORK`:
100 for points, 400 for lines, about 2.5 times the most measured to converge).

Normal film coefficients: :func:`ehl_normal_coefficients`.

References: Venner & Lubrecht, *Multilevel Methods in Lubrication*, Elsevier
2000 (dimensionless groups, domain, test cases); Habchi et al., Tribol. Int. 41
(2008) 1163 (full-system FEM EHL, SUPG); Liu, Wang & Liu, Wear 243 (2000) 101
(DC-FFT).
"""
from __future__ import annotations

import contextvars
import logging
import time
import warnings
from dataclasses import dataclass, field
from types import SimpleNamespace
from typing import NamedTuple

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from skfem import BilinearForm, LinearForm, asm
from skfem.helpers import dot, grad

from . import mesh as meshes
from .laws import contact as hertz
from .laws.contact import hamrock_brewe_radius_ratio
from .elastic import ElasticKernel
from .ehl_assembly import UniformForms
from .errors import ConvergenceError, InputError, require_positive, unknown_choice
from .laws.lubricant import Lubricant, eyring_flow_factor
from .reynolds import _advection, _diffusion, _flux_load, _mass, _source_load, _streamline, make_basis

log = logging.getLogger(__name__)

TRACTION_MODELS = ("newtonian", "limiting_shear", "eyring")


def supg_parameter(um, dx, rho, h, k):
    """Streamline-upwind parameter of the Reynolds equation at the quadrature points.

    Peclet number Pe = u_m dx rho h / (2 k), k = rho h^3/(12 eta) (so Pe = 6 u_m dx eta/h^2,
    rho cancels), capped at 1e8; tau = dx/(2 u_m) (coth Pe - 1/Pe) (Pe/3 below 1e-3) and its
    exact derivative d tau/d Pe (0 at the cap).  Returns ``(Pe, tau, dtau_dPe)``."""
    Pe_raw = um * dx * rho * h / (2 * np.maximum(k, 1e-300))
    Pe = np.minimum(Pe_raw, 1e8)
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        xi = np.where(Pe > 1e-3, 1.0 / np.tanh(np.minimum(Pe, 700)) - 1.0 / Pe, Pe / 3.0)
        sh = np.sinh(np.minimum(Pe, 300.0))
        dxi = np.where(Pe > 1e-3, 1.0 / Pe**2 - np.where(Pe < 300.0, 1.0 / sh**2, 0.0), 1.0 / 3.0)
    dxi = np.where(Pe_raw < 1e8, dxi, 0.0)
    return Pe, dx / (2 * um) * xi, dx / (2 * um) * dxi


def _log_slope(eta, deta):
    """d ln(eta)/dp, 0 where a far-off Newton iterate overflowed eta (there k = 0 and tau is capped)."""
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        r = deta / eta
    return np.where(np.isfinite(r), r, 0.0)


def _eyring_terms(lub, h, grad_p):
    """Reynolds-Eyring factors at the quadrature points (None for a Newtonian lubricant).

    ``phi`` = Phi(x), x = s |grad p|, s = h/(2 tau0) (:func:`lubrication.laws.lubricant.eyring_flow_factor`);
    ``c2`` = (Phi'/x) s^2, so that d(Phi grad p)/d(grad p) = Phi I + c2 grad p grad p^T;
    ``dphi_dh`` = dPhi/dh = (Phi'/x) x^2/h."""
    tau0 = lub.eyring_stress
    if tau0 is None:
        return None
    s = h / (2.0 * tau0)
    g2 = sum(np.asarray(grad_p[d]) ** 2 for d in range(len(grad_p)))
    x = s * np.sqrt(g2)
    phi, dphi_x = eyring_flow_factor(x)
    return {"phi": phi, "c2": dphi_x * s**2, "dphi_dh": dphi_x * x**2 / h}


@dataclass(frozen=True)
class Traction:
    """Shear law for friction.  ``newtonian``: tau = eta du/h;
    ``limiting_shear``: |tau| <= tau_L0 + gamma p; ``eyring``:
    tau = tau0 asinh(eta du/(h tau0)).  Stresses in Pa."""

    model: str = "newtonian"
    limiting_shear_stress: float = 5e6
    limiting_shear_slope: float = 0.08
    eyring_stress: float = 5e6

    def __post_init__(self):
        if self.model not in TRACTION_MODELS:
            raise unknown_choice("traction.model", self.model, TRACTION_MODELS)

    def stress(self, eta, sliding, h, p):
        """Couette shear stress [Pa] for sliding speed ``sliding`` = u2 - u1 [m/s]."""
        newt = eta * sliding / h
        if self.model == "newtonian":
            return newt
        if self.model == "limiting_shear":
            lim = self.limiting_shear_stress + self.limiting_shear_slope * np.maximum(p, 0.0)
            return np.sign(newt) * np.minimum(np.abs(newt), lim)
        return self.eyring_stress * np.arcsinh(newt / self.eyring_stress)


@dataclass(frozen=True)
class EHLContact:
    """An EHL contact (SI).

    ``radius_y=None`` makes a line contact (``load`` then in N/m).  Give
    ``load`` (load balance finds h00) or ``approach`` = h00 [m] (prescribed:
    h00 is the rigid-body separation, -h00 the approach of the bodies).
    ``slide_to_roll`` = (u2 - u1)/u_m; ``squeeze_velocity`` = dh00/dt [m/s]
    (negative: the bodies approach; the Reynolds equation gets the source
    rho dh00/dt).  ``scale_load`` [N or N/m]: with a prescribed approach, the
    load whose Hertz contact sets the grid's length scales (default 1 N or
    1 N/m); give the load of a steady state to solve on the same grid.
    """

    radius_x: float
    radius_y: float | None
    e_star: float
    lubricant: Lubricant
    mean_speed: float
    load: float | None = None
    approach: float | None = None
    slide_to_roll: float = 0.0
    squeeze_velocity: float = 0.0
    traction: Traction = Traction()
    scale_load: float | None = None

    def __post_init__(self):
        require_positive("radius_x [m]", self.radius_x)
        if self.radius_y is not None:
            require_positive("radius_y [m]", self.radius_y)
        require_positive("reduced modulus E* [Pa]", self.e_star)
        require_positive("mean (entrainment) speed [m/s]", self.mean_speed)
        if (self.load is None) == (self.approach is None):
            raise InputError("an EHL contact needs exactly one of 'load' or 'approach'")
        if self.load is not None:
            require_positive("load [N or N/m]", self.load)
        if self.scale_load is not None:
            require_positive("scale_load [N or N/m]", self.scale_load)

    @property
    def is_line(self) -> bool:
        return self.radius_y is None

    @property
    def e_prime(self) -> float:
        return 2.0 * self.e_star

    def hertz_load(self) -> float:
        """Load used for the Hertz scales (the given load, else ``scale_load``, else 1)."""
        if self.load is not None:
            return self.load
        return self.scale_load if self.scale_load is not None else 1.0

    # dimensionless groups ----------------------------------------------
    @property
    def U(self) -> float:
        """Hamrock-Dowson speed parameter eta0 u_m / (E' R_x)."""
        return self.lubricant.viscosity.eta0 * self.mean_speed / (self.e_prime * self.radius_x)

    @property
    def G(self) -> float:
        """Material parameter alpha E' (alpha: Barus, or Roelands' low-pressure slope)."""
        return self.lubricant.viscosity.pressure_viscosity * self.e_prime

    @property
    def W(self) -> float:
        """Load parameter w/(E' R_x^2) (point) or w/(E' R_x) (line)."""
        return self.hertz_load() / (self.e_prime * self.radius_x ** (1 if self.is_line else 2))

    @property
    def moes_M(self) -> float:
        return self.W * (2 * self.U) ** (-0.5 if self.is_line else -0.75)

    @property
    def moes_L(self) -> float:
        return self.G * (2 * self.U) ** 0.25

    @classmethod
    def from_moes(cls, M, L, *, radius_x=0.01, e_star=1.0e11, eta0=0.04, mean_speed=None,
                  radius_y=..., line=False, density=None, **kw):
        """A circular (or ``line``) contact with Moes parameters ``M`` and ``L``.

        Radius, modulus and viscosity are fixed; the speed follows from ``L``
        only if ``mean_speed`` is None (then alpha = L/((2U)^(1/4) E')), else
        alpha is chosen from L at that speed.  Returns a Barus lubricant.
        """
        from .laws.lubricant import Barus, Incompressible

        Ep = 2 * e_star
        if mean_speed is None:
            mean_speed = 1.0
        U = eta0 * mean_speed / (Ep * radius_x)
        alpha = L / ((2 * U) ** 0.25 * Ep)
        if line:
            load = M * (2 * U) ** 0.5 * Ep * radius_x
            ry = None
        else:
            load = M * (2 * U) ** 0.75 * Ep * radius_x**2
            ry = radius_x if radius_y is ... else radius_y
        lub = Lubricant(Barus(eta0, alpha), density or Incompressible(850.0))
        return cls(radius_x, ry, e_star, lub, mean_speed, load=load, **kw)

    @classmethod
    def from_hamrock_dowson(cls, W, U, G, k=1.0, *, radius_x=0.01, e_star=1.0e11, eta0=0.04, line=False,
                            ellipticity="exact", density=None, **kw):
        """A contact with Hamrock-Dowson groups ``W``, ``U``, ``G`` and ellipticity ``k`` = a/b.

        W = w/(E' R_x^2) (point; w/(E' R_x) with ``line=True``), U = eta0 u_m/(E' R_x),
        G = alpha E' (E' = 2 E*).  Radius, modulus and eta0 are fixed, so
        u_m = U E' R_x/eta0, alpha = G/E', w = W E' R_x^2 (or W E' R_x).  The
        radius ratio R_y/R_x (entrainment along the minor axis, k >= 1) is
        the one whose Hertz ellipse has a/b = k: exactly (``ellipticity=
        "exact"``), inverting the elliptic-integral relation of
        :mod:`lubrication.laws.contact`, R_y/R_x = (E(m)/(1 - m) - K(m))/(K(m) - E(m)),
        m = 1 - 1/k^2; or by Hamrock & Brewe's fit k = 1.0339 (R_y/R_x)^0.636
        (``"hamrock_brewe"``).  Returns a Barus lubricant.

        >>> c = EHLContact.from_hamrock_dowson(1e-6, 1e-11, 5000, 3.0)
        >>> round(c.W / 1e-6, 12), round(c.U / 1e-11, 12), round(c.G / 5000, 12)
        (1.0, 1.0, 1.0)
        """
        from scipy.special import ellipe, ellipk

        from .errors import unknown_choice
        from .laws.lubricant import Barus, Incompressible

        for key, val in (("W", W), ("U", U)):
            require_positive(f"Hamrock-Dowson {key}", val)
        if G < 0:
            raise InputError(f"Hamrock-Dowson G = {G!r} must be >= 0")
        if ellipticity not in hertz.METHODS:
            raise unknown_choice("ellipticity", ellipticity, hertz.METHODS)
        Ep = 2 * e_star
        mean_speed = U * Ep * radius_x / eta0
        lub = Lubricant(Barus(eta0, G / Ep), density or Incompressible(850.0))
        if line:
            return cls(radius_x, None, e_star, lub, mean_speed, load=W * Ep * radius_x, **kw)
        if not k >= 1.0:
            raise InputError(f"ellipticity k = {k!r} must be >= 1 (entrainment along the minor axis)")
        if ellipticity == "hamrock_brewe":
            ratio = hamrock_brewe_radius_ratio(k)
        elif k == 1.0:
            ratio = 1.0
        else:
            m = 1.0 - 1.0 / k**2
            K, E = ellipk(m), ellipe(m)
            ratio = (E / (1.0 - m) - K) / (K - E)
        return cls(radius_x, ratio * radius_x, e_star, lub, mean_speed, load=W * Ep * radius_x**2, **kw)


@dataclass(frozen=True)
class EHLGrid:
    """Uniform grid: ``nx`` x ``ny`` nodes on x in [x_min, x_max] b_x and
    |y| <= y_max b_y (b_x, b_y: Hertz semi-axes along x and y)."""

    nx: int = 129
    ny: int | None = None
    x_min: float = -4.5
    x_max: float = 1.5
    y_max: float = 3.0

    def __post_init__(self):
        if self.nx < 9:
            raise InputError(f"grid nx = {self.nx!r} must be >= 9")
        if not self.x_min < 0 < self.x_max:
            raise InputError(f"grid x range [{self.x_min}, {self.x_max}] must contain 0")


@dataclass(frozen=True)
class EHLOptions:
    rtol: float = 1e-7
    max_iter: int = 80
    dense_max: int = 1200  # point contacts; line contacts stay dense up to dense_max_line
    dense_max_line: int = 2100
    max_step: float = 2.0
    stencil: int = 1
    gmres_rtol: float = 1e-9
    h_floor: float = 1e-4  # relative to the Hertz film scale b^2/R_x
    consistent_supg: bool = True  # second-order SUPG (recovered Poiseuille flux); False: first order
    active_set_passes: int = 1  # >1: re-solve after moving newly negative nodes to the cavitated set
    max_point_grid: int = 257  # largest point-contact grid (nodes per side) measured to converge
    method: str = "auto"  # "fischer_burmeister", "active_set"; auto: FB for points, active set for lines
    line_search: int = 12  # Armijo halvings of the FB Newton step
    first_order_start: str = "auto"  # "every_grid", "coarsest"; auto: lines every grid, points coarsest
    max_damped: int = 8  # second order from a prolonged start: fall back after this many damped steps
    coarse_rtol: float = 1e-3  # FB Newton tolerance of a start (nested coarse level, first-order stage)
    coarse_max_iter: int = 30  # FB Newton iterations on a nested coarse level (only a start for the next)
    max_stalls: int = 4  # FB Newton: give up after this many stalled line searches (< 1/64 of the step)
    gmres_forcing: float = 1e-3  # largest GMRES rtol of an inexact Newton step (min with |Phi|)
    precond_refresh: int = 20  # refactorise the sparse preconditioner when GMRES needs this many iterations
    # method="multigrid": lubrication.ehl_multigrid.MultigridOptions (None: its defaults)
    multigrid: object = None
    # a-posteriori checks (closed-form film, coarser level; :func:`check_solution`): False logs a
    # WARNING and lists it in info["warnings"], True raises ConvergenceError instead (tests)
    strict: bool = False
    # work budget of one solve_ehl call, in Newton steps on the requested grid (a step on a coarser
    # level counts its share of the nodes), every start and fallback included; None: the default of
    # the contact kind, DEFAULT_MAX_WORK (math.inf: unbounded)
    max_work: float | None = None

    def __post_init__(self):
        for key, value, allowed in (("method", self.method, EHL_METHODS),
                                    ("first_order_start", self.first_order_start, FIRST_ORDER_STARTS)):
            if value not in allowed:
                raise unknown_choice(f"solver.{key}", value, allowed)
        if self.multigrid is not None:
            from .ehl_multigrid import MultigridOptions

            if not isinstance(self.multigrid, MultigridOptions):
                raise InputError(f"ehl.multigrid = {self.multigrid!r} must be a MultigridOptions (or None)")


# "multigrid": FAS multigrid of lubrication.ehl_multigrid (point contacts only)
EHL_METHODS = ("auto", "fischer_burmeister", "active_set", "multigrid")
FIRST_ORDER_STARTS = ("auto", "every_grid", "coarsest")


# ---------------------------------------------------------------- SUPG forms
@LinearForm
def _supg_load(v, w):
    return w["t"] * dot(w["u"], grad(v))


@BilinearForm
def _supg_derivative(u, v, w):
    """tau (u_m . grad v) (e . grad u): SUPG test against a directional derivative."""
    return w["t"] * dot(w["u"], grad(v)) * dot(w["e"], grad(u))


@BilinearForm
def _directional(u, v, w):
    """k (e . grad u) v."""
    return w["k"] * dot(w["e"], grad(u)) * v


class _Problem:
    def __init__(self, contact: EHLContact, grid: EHLGrid, options: EHLOptions):
        self.c, self.g, self.o = contact, grid, options
        W = contact.hertz_load()
        if contact.is_line:
            hz = hertz.line_contact(W, contact.radius_x, contact.e_star)
            self.bx, self.by, self.ph = hz.b, None, hz.p0
            self.delta_hertz = None
        else:
            hp = hertz.point_contact(W, contact.radius_x, contact.radius_y, contact.e_star)
            # hp.a lies along the larger radius
            if contact.radius_y >= contact.radius_x:
                self.bx, self.by = hp.b, hp.a
            else:
                self.bx, self.by = hp.a, hp.b
            self.ph = hp.p0
            self.delta_hertz = hp.approach
        self.hscale = self.bx**2 / contact.radius_x
        nx = grid.nx
        xs = np.linspace(grid.x_min * self.bx, grid.x_max * self.bx, nx)
        self.dx = xs[1] - xs[0]
        if contact.is_line:
            self.mesh = meshes.interval(xs[0], xs[-1], nx - 1)
            self.shape = (nx,)
            spacing = (self.dx,)
        else:
            ny = grid.ny or int(round((nx - 1) * 2 * grid.y_max * self.by / ((grid.x_max - grid.x_min) * self.bx))) + 1
            ny += (ny + 1) % 2  # odd: a node row on the centre line
            ys = np.linspace(-grid.y_max * self.by, grid.y_max * self.by, ny)
            self.dy = ys[1] - ys[0]
            self.mesh = meshes.rectangle(xs, ys, "quad")
            self.shape = (nx, ny)
            spacing = (self.dx, self.dy)
        self.xs = xs
        self.ys = None if contact.is_line else ys
        self.basis = make_basis(self.mesh, "P1")
        b = self.basis
        self.N = b.N
        loc = b.doflocs
        ix = np.rint((loc[0] - xs[0]) / self.dx).astype(int)
        if contact.is_line:
            self.flat = ix
        else:
            iy = np.rint((loc[1] - ys[0]) / self.dy).astype(int)
            self.flat = ix * self.shape[1] + iy
        self.kernel = ElasticKernel(self.shape, spacing, contact.e_star)
        x = loc[0]
        self.rigid = x**2 / (2 * contact.radius_x)
        if not contact.is_line:
            self.rigid = self.rigid + loc[1] ** 2 / (2 * contact.radius_y)
        # assembly templates and nodal weights int phi_i dA, built on first use
        # (1.6 s at 513 x 513, which the multigrid method does not need)
        self._forms = None
        self._weights = None
        dim = 1 if contact.is_line else 2
        u = np.zeros((dim,) + (b.nelems, b.X.shape[-1]))
        u[0] = contact.mean_speed
        self.u = u
        self.fixed = np.zeros(self.N, dtype=bool)
        # Dirichlet p = 0 on the whole boundary
        self.fixed[b.get_dofs(self.mesh.boundary_facets()).all()] = True
        self.free0 = ~self.fixed
        self._Kdense = None
        self._Kloc = None

    @property
    def forms(self):
        if self._forms is None:
            self._forms = UniformForms(self.basis)
        return self._forms

    @property
    def weights(self):
        """int phi_i dA [m^2 or m] of every dof (P1 on the uniform grid)."""
        if self._weights is None:
            b = self.basis
            self._weights = self.forms.vector([(np.ones((b.nelems, b.X.shape[-1])), self.forms.val)])
        return self._weights

    def uniform_weights(self):
        """The same weights without the assembly templates: dx dy (or dx) times the
        number of cells at the node over the number of a cell's vertices (P1 on
        a uniform tensor grid; equal to :attr:`weights` to round-off)."""
        if self._weights is None:
            if self.c.is_line:
                w = np.full(self.shape, self.dx)
                w[[0, -1]] *= 0.5
            else:
                w = np.full(self.shape, self.dx * self.dy)
                w[[0, -1], :] *= 0.5
                w[:, [0, -1]] *= 0.5
            self._weights = w.ravel()[self.flat]
        return self._weights

    # -- elastic operator in dof ordering --------------------------------
    def deflect(self, p):
        grid = np.zeros(np.prod(self.shape))
        grid[self.flat] = p
        u = self.kernel.deflect(grid.reshape(self.shape)).ravel()
        return u[self.flat]

    def K_dense(self):
        if self._Kdense is None:
            Kk = self.kernel._kernel
            if self.c.is_line:
                i = self.flat
                M = Kk[i[:, None] - i[None, :] + self.shape[0] - 1]
            else:
                ny = self.shape[1]
                ix, iy = self.flat // ny, self.flat % ny
                M = Kk[ix[:, None] - ix[None, :] + self.shape[0] - 1, iy[:, None] - iy[None, :] + ny - 1]
            self._Kdense = M
        return self._Kdense

    def K_local(self):
        """Sparse truncation of K to offsets |di|, |dj| <= stencil."""
        if self._Kloc is None:
            s = self.o.stencil
            Kk = self.kernel._kernel
            rows, cols, vals = [], [], []
            if self.c.is_line:
                n = self.shape[0]
                inv = np.empty(n, dtype=int)
                inv[self.flat] = np.arange(self.N)
                for d in range(-s, s + 1):
                    i = np.arange(max(0, -d), min(n, n - d))
                    rows.append(inv[i]); cols.append(inv[i + d]); vals.append(np.full(i.size, Kk[d + n - 1]))
            else:
                nx, ny = self.shape
                inv = np.empty(nx * ny, dtype=int)
                inv[self.flat] = np.arange(self.N)
                I, J = np.meshgrid(np.arange(nx), np.arange(ny), indexing="ij")
                for di in range(-s, s + 1):
                    for dj in range(-s, s + 1):
                        ok = (I + di >= 0) & (I + di < nx) & (J + dj >= 0) & (J + dj < ny)
                        a = (I[ok] * ny + J[ok])
                        bb = ((I[ok] + di) * ny + J[ok] + dj)
                        rows.append(inv[a]); cols.append(inv[bb])
                        vals.append(np.full(a.size, Kk[di + nx - 1, dj + ny - 1]))
            self._Kloc = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(self.N, self.N))
        return self._Kloc

    # -- residual and Jacobian blocks ------------------------------------
    def film(self, p, h00):
        return h00 + self.rigid + self.deflect(p)

    def _coefficients(self, pq, hq, grad_p):
        """Pointwise coefficients at the quadrature points, shared by both assemblies: eta, eta',
        rho, rho', kN = rho h^3/(12 eta), the Eyring factors ``ey`` (:func:`_eyring_terms`, None if
        Newtonian), k = kN Phi, and the SUPG parameter (Pe = 6 u_m l eta/(h^2 Phi), rho cancels;
        tau, tau'(Pe))."""
        lub = self.c.lubricant
        with np.errstate(over="ignore", invalid="ignore"):
            eta, deta = lub.viscosity(pq), lub.viscosity.derivative(pq)
            rho, drho = lub.density(pq), lub.density.derivative(pq)
        kN = rho * hq**3 / (12 * eta)
        ey = _eyring_terms(lub, hq, grad_p)
        k = kN if ey is None else kN * ey["phi"]
        Pe, tau, dtau_dPe = supg_parameter(self.c.mean_speed, self.dx, rho, hq, k)
        return SimpleNamespace(eta=eta, deta=deta, rho=rho, drho=drho, kN=kN, ey=ey, k=k, Pe=Pe, tau=tau,
                               dtau_dPe=dtau_dPe)

    def _coefficient_derivatives(self, cf, pq, hq):
        """dk/dp, dk/dh, dtau/dp, dtau/dh at fixed grad p (the grad p terms of Eyring flow are
        assembled by the callers), and rho'' (None for a pressure-independent density).

        d tau/dp = tau'(Pe) Pe eta'/eta, d tau/dh = -tau'(Pe) Pe (2/h + Phi_h/Phi); with Eyring flow
        k = kN Phi(x), x = h |grad p|/(2 tau0), so dk/dh gains kN Phi' x/h.  rho'' by a central
        difference on the smooth branch p > 0 (rho' jumps at p = 0, where rho = rho(max(p, 0)) has
        rho'' = 0 on the flat side)."""
        eta, rho, drho, kN, ey, Pe, dtau_dPe = cf.eta, cf.rho, cf.drho, cf.kN, cf.ey, cf.Pe, cf.dtau_dPe
        dlog_eta = _log_slope(eta, cf.deta)
        dk_dp = hq**3 / 12 * (drho - rho * dlog_eta) / eta
        dk_dh = rho * 3 * hq**2 / (12 * eta)
        dtau_dp = dtau_dPe * Pe * dlog_eta
        dtau_dh = -2.0 * dtau_dPe * Pe / hq
        if ey is not None:
            dk_dp = dk_dp * ey["phi"]
            dk_dh = dk_dh * ey["phi"] + kN * ey["dphi_dh"]
            dtau_dh = dtau_dh - dtau_dPe * Pe * ey["dphi_dh"] / ey["phi"]
        d2rho = None
        if np.any(drho != 0.0):
            density = self.c.lubricant.density
            dp_ = 1e-6 * self.ph
            lo, hi = np.maximum(pq - dp_, 0.5 * pq), pq + dp_
            with np.errstate(invalid="ignore", divide="ignore"):
                d2rho = np.where(pq > 0, (density.derivative(hi) - density.derivative(lo)) / (hi - lo), 0.0)
        return dk_dp, dk_dh, dtau_dp, dtau_dh, d2rho

    def assemble(self, p, h00, jac=True):
        """Residual R(p, h00) of the stabilised Reynolds equation and, with
        ``jac``, its exact derivatives A = dR/dp at fixed film and D = dR/dh
        (nodal film), vectorised on the uniform grid (:mod:`lubrication.ehl_assembly`;
        :meth:`assemble_skfem` is the same with scikit-fem forms, for checks)."""
        c, F = self.c, self.forms
        hn = self.film(p, h00)
        hfloor = self.o.h_floor * self.hscale
        hn_eff = np.maximum(hn, hfloor)
        pv, pg = F.interpolate(p)
        hq, hg = F.interpolate(hn_eff)
        pq = np.maximum(pv, 0.0)
        cf = self._coefficients(pq, hq, pg)
        rho, drho, kN, ey, k, Pe, tau, dtau_dPe = cf.rho, cf.drho, cf.kN, cf.ey, cf.k, cf.Pe, cf.tau, cf.dtau_dPe
        um = c.mean_speed
        hdot = c.squeeze_velocity
        dim = F.dim
        strong = um * (rho * hg[0] + hq * drho * pg[0]) + rho * hdot
        if self.o.consistent_supg:
            # recovered Poiseuille flux F = -k grad p at the nodes (lumped L2
            # projection); its divergence completes the strong residual, so the
            # SUPG term is consistent and the scheme second order
            for d in range(dim):
                Fd = -F.vector([(k * pg[d], F.val)]) / self.weights
                strong = strong + F.interpolate(Fd)[1][d]
        # R_i = int (k grad p - rho h u_m + tau strong u_m) . grad v_i + rho hdot v_i
        terms = [(k * pg[d], F.grd[d]) for d in range(dim)]
        terms[0] = (k * pg[0] - rho * hq * um + tau * strong * um, F.grd[0])
        if hdot != 0.0:
            terms.append((rho * hdot, F.val))
        R = F.vector(terms)
        if not jac:
            return R, hn
        dk_dp, dk_dh, dtau_dp, dtau_dh, d2rho = self._coefficient_derivatives(cf, pq, hq)
        # d(strong)/dp_j without the film dependence (that is in D):
        # u_m (rho' h_x + h rho'' p_x) phi_j + u_m rho' h d_x phi_j + rho' hdot phi_j
        if d2rho is not None:
            d_strong_dp = um * (drho * hg[0] + hq * d2rho * pg[0]) + drho * hdot
        else:
            d_strong_dp = 0.0
        # A: diffusion k, advection (k' grad p - rho' h u) phi_j . grad v, the
        # squeeze mass rho' hdot, SUPG: tau (d strong/dp) u.grad v + tau' strong u.grad v
        Aterms = [(k, F.gg[d][d]) for d in range(dim)]
        Aterms += [(dk_dp * pg[d], F.adv[d]) for d in range(dim)]
        if ey is not None:
            c2 = kN * ey["c2"]
            Aterms += [(c2 * pg[d] * pg[e], F.gg[d][e]) for d in range(dim) for e in range(dim)]
            # tau(Pe(grad p)): d tau/d(d_e p) = -tau'(Pe) Pe c2/k d_e p, times strong u_m . grad v
            Aterms += [(-dtau_dPe * Pe * ey["c2"] / ey["phi"] * pg[e] * strong * um, F.gg[0][e]) for e in range(dim)]
        Aterms.append((-drho * hq * um + (tau * d_strong_dp + dtau_dp * strong) * um, F.adv[0]))
        Aterms.append((tau * drho * hq * um * um, F.gg[0][0]))
        if hdot != 0.0:
            Aterms.append((drho * hdot, F.mass))
        Dterms = [(dk_dh * pg[d], F.adv[d]) for d in range(dim)]
        Dterms.append((-rho * um + (tau * um * drho * pg[0] + dtau_dh * strong) * um, F.adv[0]))
        Dterms.append((tau * rho * um * um, F.gg[0][0]))
        A = F.matrix(Aterms)
        D = F.matrix(Dterms)
        if self.o.consistent_supg:
            Ml_inv = sp.diags(1.0 / self.weights)
            for d in range(dim):
                S = F.matrix([(tau * um, F.gg[0][d])])
                gp_terms = [(k, F.dirn[d]), (dk_dp * pg[d], F.mass)]
                if ey is not None:
                    gp_terms += [(c2 * pg[d] * pg[e], F.dirn[e]) for e in range(dim)]
                Gp = F.matrix(gp_terms)
                Gh = F.matrix([(dk_dh * pg[d], F.mass)])
                SM = S @ Ml_inv
                A = A - SM @ Gp
                D = D - SM @ Gh
            A, D = A.tocsr(), D.tocsr()
        # nodes whose film sits on the floor do not feel h changes
        D = D @ sp.diags((hn > hfloor).astype(float))
        return R, hn, A, D, dict(tau=tau, rho=rho)

    def assemble_skfem(self, p, h00, jac=True):
        """Reference assembly with scikit-fem forms (the same equations as :meth:`assemble`)."""
        c, b = self.c, self.basis
        hn = self.film(p, h00)
        hfloor = self.o.h_floor * self.hscale
        hn_eff = np.maximum(hn, hfloor)
        pf, hf = b.interpolate(p), b.interpolate(hn_eff)
        pq, hq = np.maximum(np.asarray(pf), 0.0), np.asarray(hf)
        cf = self._coefficients(pq, hq, np.asarray(pf.grad))
        rho, drho, kN, ey, k, Pe, tau, dtau_dPe = cf.rho, cf.drho, cf.kN, cf.ey, cf.k, cf.Pe, cf.tau, cf.dtau_dPe
        um = c.mean_speed
        u = self.u
        hdot = c.squeeze_velocity
        ugrad_rho_h = um * (rho * hf.grad[0] + hq * drho * pf.grad[0])
        strong = ugrad_rho_h + rho * hdot
        dim = 1 if c.is_line else 2
        if self.o.consistent_supg:
            # recovered Poiseuille flux F = -k grad p at the nodes (lumped L2
            # projection); its divergence completes the strong residual, so the
            # SUPG term is consistent and the scheme second order
            div = 0.0
            for d in range(dim):
                Fd = -np.asarray(asm(_source_load, b, g=k * pf.grad[d])) / self.weights
                div = div + b.interpolate(Fd).grad[d]
            strong = strong + div
        Kd = asm(_diffusion, b, a=k)
        R = Kd @ p + asm(_flux_load, b, f=-rho * hq * u) + asm(_source_load, b, g=rho * hdot)
        R = R + asm(_supg_load, b, t=tau * strong, u=u)
        if not jac:
            return R, hn
        dk_dp, dk_dh, dtau_dp, dtau_dh, d2rho = self._coefficient_derivatives(cf, pq, hq)
        # d(strong)/dp_j without the h-dependence (in D): u_m (rho' h_x + h rho'' p_x)
        # phi_j + (rho' h u_m) . grad phi_j + rho' hdot phi_j
        if d2rho is not None:
            d_strong_dp = um * (drho * hf.grad[0] + hq * d2rho * pf.grad[0]) + drho * hdot
        else:
            d_strong_dp = 0.0 * hq
        A = (
            Kd
            + asm(_advection, b, b=dk_dp * pf.grad - drho * hq * u)
            + asm(_mass, b, c=drho * hdot * np.ones_like(hq))
            + asm(_streamline, b, s=tau * drho * hq, beta=u)
            + asm(_advection, b, b=(tau * d_strong_dp + dtau_dp * strong) * u)
        )
        if ey is not None:
            gp = np.asarray(pf.grad)
            c2 = kN * ey["c2"]
            # c2 (grad p . grad phi_j)(grad p . grad v) and d tau/d(grad p) strong (u . grad v)
            A = (A + asm(_supg_derivative, b, t=c2, u=gp, e=gp)
                 + asm(_supg_derivative, b, t=-dtau_dPe * Pe * ey["c2"] / ey["phi"] * strong, u=u, e=gp))
        A = A.tocsr()
        D = (
            asm(_advection, b, b=dk_dh * pf.grad - rho * u)
            + asm(_streamline, b, s=tau * rho, beta=u)
            + asm(_advection, b, b=(tau * um * drho * pf.grad[0] + dtau_dh * strong) * u)
        ).tocsr()
        if self.o.consistent_supg:
            Ml_inv = sp.diags(1.0 / self.weights)
            for d in range(dim):
                e = np.zeros_like(u)
                e[d] = 1.0
                S = asm(_supg_derivative, b, t=tau, u=u, e=e)
                Gp = asm(_directional, b, k=k, e=e) + asm(_mass, b, c=dk_dp * pf.grad[d])
                if ey is not None:
                    Gp = Gp + asm(_directional, b, k=c2 * gp[d], e=gp)
                Gh = asm(_mass, b, c=dk_dh * pf.grad[d])
                A = A - S @ (Ml_inv @ Gp)
                D = D - S @ (Ml_inv @ Gh)
            A, D = A.tocsr(), D.tocsr()
        # nodes whose film sits on the floor do not feel h changes
        D = D @ sp.diags((hn > hfloor).astype(float))
        return R, hn, A, D, dict(tau=tau, rho=rho)


@dataclass
class EHLSolution:
    """Converged EHL contact.  Arrays are on the dofs of ``problem.basis``."""

    contact: EHLContact
    problem: object
    pressure: np.ndarray
    film_thickness: np.ndarray
    h00: float
    info: dict = field(default_factory=dict)

    @property
    def deflection(self) -> np.ndarray:
        return self.problem.deflect(self.pressure)

    def _centre_line(self, values):
        P = self.problem
        loc = P.basis.doflocs
        on = np.ones(P.N, dtype=bool) if P.c.is_line else np.abs(loc[1]) < 0.5 * P.dy
        order = np.argsort(loc[0][on])
        return loc[0][on][order], values[on][order]

    @property
    def central_film_thickness(self) -> float:
        """h at x = y = 0 [m]."""
        P = self.problem
        d = np.linalg.norm(P.basis.doflocs, axis=0)
        return float(self.film_thickness[np.argmin(d)])

    @property
    def minimum_film_thickness(self) -> float:
        return float(np.min(self.film_thickness))

    @property
    def maximum_pressure(self) -> float:
        return float(np.max(self.pressure))

    @property
    def pressure_spike_position(self) -> float:
        """x [m] of the pressure spike: the most downstream local maximum of the
        centre-line pressure with x > 0 (the global maximum if there is none)."""
        x, p = self._centre_line(self.pressure)
        inner = np.flatnonzero((p[1:-1] > p[:-2]) & (p[1:-1] >= p[2:]) & (x[1:-1] > 0)) + 1
        if inner.size:
            return float(x[inner[-1]])
        return float(x[np.argmax(p)])

    @property
    def load(self) -> float:
        return float(self.problem.weights @ self.pressure)

    def _shear_integrals(self):
        P, c = self.problem, self.contact
        b = P.basis
        pf = b.interpolate(self.pressure)
        pq = np.maximum(np.asarray(pf), 0.0)
        hq = np.asarray(b.interpolate(np.maximum(self.film_thickness, P.o.h_floor * P.hscale)))
        eta = c.lubricant.viscosity(pq)
        sliding = c.slide_to_roll * c.mean_speed
        couette = c.traction.stress(eta, sliding, hq, pq)
        poiseuille = -0.5 * hq * pf.grad[0]
        ones = np.ones(P.N)
        return (float(asm(_source_load, b, g=couette) @ ones), float(asm(_source_load, b, g=poiseuille) @ ones))

    def friction(self) -> float:
        """Sliding (Couette) friction force [N, or N/m for lines] that the fluid
        exerts on the slower surface, from the chosen traction law."""
        return self._shear_integrals()[0]

    def rolling_resistance(self) -> float:
        """Poiseuille shear force -(h/2) dp/dx integrated [N or N/m] (rolling friction)."""
        return self._shear_integrals()[1]

    def traction_coefficient(self) -> float:
        return self.friction() / self.load

    def to_pyvista(self):
        """Grid with 3-D points (z = 0) and point data "Pressure [Pa]",
        "Film thickness [m]", "Elastic deflection [m]"."""
        import pyvista as pv

        P = self.problem
        pts = np.zeros((P.N, 3))
        pts[:, : P.basis.doflocs.shape[0]] = P.basis.doflocs.T
        t = P.mesh.t
        nv = t.shape[0]
        kind = pv.CellType.LINE if nv == 2 else pv.CellType.QUAD
        cells = np.hstack([np.full((t.shape[1], 1), nv), t.T]).ravel()
        grid = pv.UnstructuredGrid(cells, np.full(t.shape[1], kind, dtype=np.uint8), pts)
        # P1 on a tensor mesh: dof i is vertex i
        grid.point_data["Pressure [Pa]"] = self.pressure
        grid.point_data["Film thickness [m]"] = self.film_thickness
        grid.point_data["Elastic deflection [m]"] = self.deflection
        return grid

    def save(self, path):
        """Write the fields to a ``.vtu`` file (temporary file + rename)."""
        from .solution import write_vtu

        return write_vtu(self.to_pyvista(), path)

    def plot_profiles(self):
        """Centre-line pressure and film thickness against x/b.  Returns the figure."""
        import matplotlib

        matplotlib.use("Agg", force=False)
        import matplotlib.pyplot as plt

        P = self.problem
        x, p = self._centre_line(self.pressure)
        _, h = self._centre_line(self.film_thickness)
        fig, ax = plt.subplots(figsize=(6.4, 4.0), constrained_layout=True)
        ax.plot(x / P.bx, p / 1e9, "C0-", label="pressure")
        ax.set_xlabel("x / b [-]")
        ax.set_ylabel("Pressure [GPa]", color="C0")
        ax2 = ax.twinx()
        ax2.plot(x / P.bx, h * 1e6, "C1-", label="film thickness")
        ax2.set_ylabel("Film thickness [um]", color="C1")
        ax2.set_ylim(0, 4 * self.central_film_thickness * 1e6)
        ax.set_title(f"EHL centre line (M = {self.contact.moes_M:.3g}, L = {self.contact.moes_L:.3g})")
        return fig

    def summary(self) -> dict:
        c = self.contact
        out = {
            "Central film thickness [m]": self.central_film_thickness,
            "Minimum film thickness [m]": self.minimum_film_thickness,
            "Maximum pressure [Pa]": self.maximum_pressure,
            "Hertz pressure [Pa]": float(self.problem.ph),
            "Pressure spike position [m]": self.pressure_spike_position,
            "Load [N]" if not c.is_line else "Load per length [N/m]": self.load,
            "Approach h00 [m]": float(self.h00),
            "Friction [N]" if not c.is_line else "Friction per length [N/m]": self.friction(),
            "Traction coefficient [-]": self.traction_coefficient(),
            "Rolling resistance [N]" if not c.is_line else "Rolling resistance per length [N/m]": self.rolling_resistance(),
            "Moes M [-]": c.moes_M,
            "Moes L [-]": c.moes_L,
            ("Multigrid cycles [-]" if self.info.get("method") == "multigrid" else "Newton iterations [-]"):
                int(self.info.get("iterations", 0)),
            "Solve time [s]": float(self.info.get("wall_time", 0.0)),
        }
        return out


def _hertz_guess(P: _Problem):
    loc = P.basis.doflocs
    r2 = (loc[0] / P.bx) ** 2
    if not P.c.is_line:
        r2 = r2 + (loc[1] / P.by) ** 2
    return P.ph * np.sqrt(np.clip(1 - r2, 0, None))


def _film_guess(c: EHLContact) -> float:
    """Central film thickness start value [m].

    Line contacts: Dowson-Toyoda, floored by an order-of-magnitude rigid
    estimate 8 U/W.  Point contacts: Nijenbanning-Venner-Moes (all four
    regimes, circular), times Hamrock-Dowson's ellipticity factor
    (1 - 0.61 exp(-0.73 k)) / (1 - 0.61 exp(-0.73)) for k = (R_y/R_x)^(2/pi).
    (The former point-contact start, Hamrock-Dowson floored by 8 U/W, was
    3 to 17 times too thick for M = 20 ... 200, L = 10, and its Newton
    iteration did not recover: measured failures at M = 40, 50, 100 on 33 x 33.)
    """
    from .laws.film import dowson_toyoda_central, nijenbanning_central

    U, G, W = c.U, max(c.G, 1e-3), c.W
    if c.is_line:
        H = dowson_toyoda_central(U, G, W)
        return max(H, 8 * U / W) * c.radius_x
    k = (c.radius_y / c.radius_x) ** (2 / np.pi)
    shape = (1 - 0.61 * np.exp(-0.73 * k)) / (1 - 0.61 * np.exp(-0.73))
    return float(nijenbanning_central(c.moes_M, max(c.moes_L, 1e-6)) * np.sqrt(2 * U) * shape) * c.radius_x


def _stopped(reason: str, message: str) -> ConvergenceError:
    """A :class:`ConvergenceError` carrying its stop reason (``.stop``: reason and detail)."""
    err = ConvergenceError(message)
    err.stop = dict(reason=reason, detail=message)
    return err


def _lu_factor(J, P: _Problem):
    """Dense LU of a Newton matrix; an exactly singular one (an iterate that has left the
    solution's basin, e.g. every node cavitated) raises ConvergenceError, which the start and
    fallback chain of :func:`solve_ehl` handles, instead of scipy's LinAlgWarning and a
    non-finite step."""
    with warnings.catch_warnings():
        warnings.simplefilter("error", sla.LinAlgWarning)
        try:
            return sla.lu_factor(J, check_finite=False)
        except sla.LinAlgWarning as exc:
            raise _stopped("singular Jacobian", f"EHL Newton: singular Jacobian at M = {P.c.moes_M:.4g}, "
                                   f"L = {P.c.moes_L:.4g} ({exc})") from None


class _Linear:
    """Dense LU or ILU-preconditioned GMRES for J = A + D K restricted to ``idx``."""

    def __init__(self, P: _Problem, A, D, idx):
        self.P, self.idx = P, idx
        n = idx.size
        self.dense = n <= (P.o.dense_max_line if P.c.is_line else P.o.dense_max)
        if self.dense:
            K = P.K_dense()
            J = A[idx][:, idx].toarray() + (D[idx] @ K[:, idx])
            self.lu = _lu_factor(J, P)
        else:
            self.A, self.D = A, D
            Pm = (A + D @ P.K_local())[idx][:, idx].tocsc()
            self.ilu = spla.spilu(Pm, drop_tol=1e-6, fill_factor=20)
            full = np.zeros(P.N)

            def mv(v):
                full[:] = 0.0
                full[idx] = v
                return (A @ full + D @ P.deflect(full))[idx]

            self.op = spla.LinearOperator((n, n), matvec=mv, dtype=float)
            self.M = spla.LinearOperator((n, n), matvec=self.ilu.solve, dtype=float)
            self.gmres_iters = 0

    def solve(self, rhs):
        if self.dense:
            return sla.lu_solve(self.lu, rhs, check_finite=False)
        count = [0]

        def cb(_):
            count[0] += 1

        x, info = spla.gmres(self.op, rhs, M=self.M, rtol=self.P.o.gmres_rtol, atol=0.0, restart=80, maxiter=20,
                             callback=cb, callback_type="pr_norm")
        self.gmres_iters += count[0]
        if info != 0:
            log.warning("EHL GMRES did not reach rtol %.1e (%d iterations)", self.P.o.gmres_rtol, count[0])
        return x


def _grid_values(P: _Problem, values):
    out = np.zeros(np.prod(P.shape))
    out[P.flat] = values
    return out.reshape(P.shape)


def _prolong(coarse: EHLSolution, P: _Problem) -> np.ndarray:
    """Coarse-grid pressure interpolated (multilinear) onto the dofs of ``P``."""
    from scipy.interpolate import RegularGridInterpolator

    Pc = coarse.problem
    axes = (Pc.xs,) if Pc.c.is_line else (Pc.xs, Pc.ys)
    f = RegularGridInterpolator(axes, _grid_values(Pc, coarse.pressure), bounds_error=False, fill_value=0.0)
    return f(P.basis.doflocs.T)


def _active_set_newton(P: _Problem, p, h00, W):
    """Bordered Newton with a projected active set (the module docstring's
    scheme; line contacts by default).  Returns ``(p, h00, history, gmres)``."""
    options, contact = P.o, P.c
    balance = W is not None
    cav = np.zeros(P.N, dtype=bool)
    history = []
    gm = 0
    rejected = None
    for it in range(1, options.max_iter + 1):
        _spend(P)
        R, hn, A, D, aux = P.assemble(p, h00)
        added_any = False
        for _inner in range(options.active_set_passes):
            # Newton step with the cavitated set fixed at p = 0; free nodes the
            # step would drive negative join the set and the step is recomputed
            free = P.free0 & ~cav
            idx = np.flatnonzero(free)
            lin = _Linear(P, A, D, idx)
            dpc = np.zeros(P.N)
            dpc[cav] = -p[cav]
            rhs = -R[idx] - ((A @ dpc + D @ P.deflect(dpc))[idx] if cav.any() else 0.0)
            z1 = lin.solve(rhs)
            dp = dpc.copy()
            dh = 0.0
            if balance:
                z2 = lin.solve(-(D @ np.ones(P.N))[idx])
                wv = P.weights[idx]
                load_err = P.weights @ (p + dp) - W
                denom = wv @ z2
                if not (np.isfinite(denom) and denom != 0.0):  # no free node responds to the approach
                    dh = 0.0
                    dp[idx] = z1
                else:
                    dh = -(wv @ z1 + load_err) / denom
                    dp[idx] = z1 + dh * z2
            else:
                dp[idx] = z1
            gm += getattr(lin, "gmres_iters", 0)
            neg = free & (p + dp < -1e-9 * P.ph)
            if not neg.any():
                break
            cav = cav | neg
            added_any = True
        # convergence on the full (undamped) Newton step, before any line search: at the round-off
        # floor the residual norm is noise, so a backtracking test there can halve omega at random
        # and an omega == 1 requirement never be met (tests/test_roundoff.py)
        # pressure scale: p_Hertz, or the largest pressure where that is smaller (nearly rigid,
        # hydrodynamic contacts), as in the Fischer-Burmeister scheme
        pmax = float(np.max(p))
        p_ref = P.ph if pmax <= 0 else min(P.ph, pmax)
        full = (np.max(np.abs(dp)) / p_ref, abs(dh) / P.hscale)
        if full[0] <= options.rtol and full[1] <= options.rtol:
            p_try, h_try = np.maximum(p + dp, 0.0), h00 + dh
            load_rel = abs(P.weights @ p_try - W) / W if balance else 0.0
            R_try = P.assemble(p_try, h_try, jac=False)[0]
            mult = _largest_negative_multiplier(P, A, D, R_try, cav, p_ref)
            load_tol = max(options.rtol, 1e-10) * 10
            if load_rel <= load_tol and mult <= options.rtol:
                p, h00 = p_try, h_try
                history.append((full[0], full[1], load_rel, int(cav.sum())))
                P.stop = dict(reason="tolerance met", detail=(
                    f"full Newton step max|dp|/p_ref {full[0]:.1e}, |dh00|/(b^2/R_x) {full[1]:.1e} <= rtol "
                    f"{options.rtol:.0e}, load error {load_rel:.1e} <= {load_tol:.0e}, cavitated multipliers >= "
                    f"-{options.rtol:.0e} p_ref ({int(cav.sum())} cavitated nodes) after {it} iterations"))
                log.debug("EHL %d: full step |dp|/ph = %.2e, dh00/hs = %.2e, load err %.2e: converged",
                          it, full[0], full[1], load_rel)
                break
            # the step met the tolerance, the state did not: remember which test refused it
            rejected = dict(iteration=it, load=(load_rel, load_tol), multiplier=(mult, options.rtol))
        # damping: cap the pressure change at max_step p_Hertz, then backtrack
        # on the free-node residual norm (at most 4 halvings); p + omega dp >= 0
        # on free nodes up to round-off because p >= 0 and p + dp >= 0 there
        omega = 1.0 / max(np.max(np.abs(dp)) / (options.max_step * P.ph), 1.0)
        # (a trial far outside the basin can overflow the norm: inf is "no decrease", no warning)
        with np.errstate(over="ignore"):
            r0 = np.linalg.norm(R[idx])
        for _ in range(4):
            trial = np.maximum(p + omega * dp, 0.0)
            Rt = P.assemble(trial, h00 + omega * dh, jac=False)[0]
            with np.errstate(over="ignore"):
                decreased = np.linalg.norm(Rt[idx]) <= r0
            if decreased or r0 == 0.0:
                break
            omega *= 0.5
        p_new = np.maximum(p + omega * dp, 0.0)
        h00 = h00 + omega * dh
        cav_new = cav.copy()
        if cav.any() and not added_any:
            # release cavitated nodes whose multiplier is negative, but only in
            # iterations that cavitated no new node (otherwise the set flips)
            Rn = Rt  # residual at (p_new, h00): the accepted line-search trial
            release = cav & (Rn < 0)
            cav_new &= ~release
        dmax = omega * np.max(np.abs(dp)) / P.ph
        p, cav = p_new, cav_new
        load_rel = abs(P.weights @ p - W) / W if balance else 0.0
        history.append((dmax, omega * abs(dh) / P.hscale, load_rel, int(cav.sum())))
        log.debug("EHL %d: |dp|/ph = %.2e, dh00/hs = %.2e, load err %.2e, omega %.2f, cav %d",
                  it, dmax, history[-1][1], load_rel, omega, cav.sum())
        if not np.all(np.isfinite(p)):
            raise _stopped("non-finite pressure",
                           f"EHL Newton iteration {it}: non-finite pressure (M = {contact.moes_M:.4g})")
    else:
        err = ConvergenceError(
            f"EHL solve did not converge in {options.max_iter} Newton iterations at M = {contact.moes_M:.4g}, "
            f"L = {contact.moes_L:.4g} ({P.N} nodes): last |dp|/p_Hertz = {history[-1][0]:.2e}, load error "
            f"{history[-1][2]:.2e}; {_iteration_limit_hint(P, history, rejected, hn)} (solver.max_iter)")
        err.stop = dict(reason="iteration limit", detail=str(err))
        raise err
    return p, h00, history, gm


# Moes M up to which a line contact's outlet constriction is resolved by nx nodes, measured (the
# sweep of tests/test_ehl_limits.py's docstring: Moes line M = 10 ... 1000, L = 5 ... 20, active
# set, against 1025 nodes): 129 nodes are within 3 % up to M = 100, 257 up to M = 300 (+19 % at
# M = 500, +86 % at M = 1000), 513 up to M = 1000; M_resolved = (nx - 1)^2/220 (74, 298, 1191).
def _resolved_line_M(nx):
    return (nx - 1) ** 2 / 220.0


def _iteration_limit_hint(P: _Problem, history, rejected, hn):
    """What stopped an active-set iteration at its limit, computed from the state: the test that
    refused a converged step (with its figures), active-set cycling (the cavitated counts), a film at
    the floor, and a finer grid only where the load parameter asks for one."""
    o, c = P.o, P.c
    parts = []
    if rejected is not None:
        (le, lt), (mu, mt) = rejected["load"], rejected["multiplier"]
        failed = []
        if le > lt:
            failed.append(f"the load error {le:.1e} > {lt:.0e}")
        if mu > mt:
            failed.append(f"a cavitated node's multiplier -{mu:.1e} p_ref below -{mt:.0e}")
        parts.append(f"the Newton step met rtol {o.rtol:.0e} (last at iteration {rejected['iteration']}) but "
                     + " and ".join(failed) + " refused the state")
    else:
        tail = [h[0] for h in history[-5:]]
        parts.append(f"the full step never met rtol {o.rtol:.0e} (last five max|dp|/p_Hertz "
                     + ", ".join(f"{v:.1e}" for v in tail) + ")")
    counts = [h[3] for h in history[-10:]]
    if len(counts) >= 6 and len(set(counts[-6:])) > 1 and max(counts[-6:]) - min(counts[-6:]) > 0 \
            and len(set(counts[-6:])) <= 3:
        parts.append(f"the cavitated set keeps changing ({min(counts[-6:])} ... {max(counts[-6:])} nodes over the "
                     "last six steps)")
    if np.min(hn) <= o.h_floor * P.hscale * 1.0001:
        parts.append("the film reached the floor")
    nx = P.shape[0]
    if c.is_line and c.load is not None and c.moes_M > _resolved_line_M(nx):
        finer = nx
        while c.moes_M > _resolved_line_M(finer):
            finer = 2 * (finer - 1) + 1
        parts.append(f"M = {c.moes_M:.4g} is beyond what {nx} nodes resolve (about M <= "
                     f"{_resolved_line_M(nx):.0f}): use grid.nx >= {finer}")
    return "; ".join(parts)


class _FBLinear:
    """Linear solver of the Fischer-Burmeister Newton step on the free (interior) dofs ``idx``::

        J = diag(a') + diag(b' s) (A + D K)     (a' = dphi/da / p_ref, given scaled)

    dense LU up to ``dense_max`` unknowns; otherwise restarted GMRES with
    FFT products (K applied by :meth:`_Problem.deflect`), right-preconditioned
    by the sparse LU (``splu``) of the same matrix with K replaced by its
    local truncation ``K_local`` (offsets up to ``EHLOptions.stencil``),
    factorised once per Newton step.
    """

    def __init__(self, P: _Problem, A, D, da, dbs, idx, reuse=None, rtol=None):
        self.P, self.idx = P, idx
        self.rtol = P.o.gmres_rtol if rtol is None else rtol
        self.refactored = False
        n = idx.size
        self.dense = n <= (P.o.dense_max_line if P.c.is_line else P.o.dense_max)
        self.gmres_iters = 0
        if self.dense:
            K = P.K_dense()
            J = A[idx][:, idx].toarray() + (D[idx] @ K[:, idx])
            J *= dbs[:, None]
            J[np.arange(n), np.arange(n)] += da
            self.lu = _lu_factor(J, P)
            return
        self._parts = (A, D, da, dbs)
        if reuse is not None:
            self.lu = reuse
        else:
            self._factorise()
        full = np.zeros(P.N)

        def mv(v):
            full[:] = 0.0
            full[idx] = v
            return dbs * (A @ full + D @ P.deflect(full))[idx] + da * v

        self.op = spla.LinearOperator((n, n), matvec=mv, dtype=float)
        self.M = spla.LinearOperator((n, n), matvec=self.lu.solve, dtype=float)

    def solve(self, rhs):
        if self.dense:
            return sla.lu_solve(self.lu, rhs, check_finite=False)
        count = [0]

        def cb(_):
            count[0] += 1

        x, info = spla.gmres(self.op, rhs, M=self.M, rtol=self.rtol, atol=0.0, restart=60,
                             maxiter=10, callback=cb, callback_type="pr_norm")
        self.gmres_iters += count[0]
        self.last_iters = count[0]
        if info != 0:
            log.debug("EHL GMRES did not reach rtol %.1e (%d iterations)", self.rtol, count[0])
        return x

    def _factorise(self):
        A, D, da, dbs = self._parts
        Jl = (A + D @ self.P.K_local())[self.idx][:, self.idx]
        Pm = (sp.diags(dbs) @ Jl + sp.diags(da)).tocsc()
        # minimum degree on A^T + A: 3-4 times less fill and time than COLAMD here
        self.lu = spla.splu(Pm, permc_spec="MMD_AT_PLUS_A")
        self.refactored = True

    def solve_bordered(self, rhs, col, row, rhs_row):
        """Solve [[J, col], [row^T, 0]] [x; t] = [rhs; rhs_row] (the load-balance
        border).  Dense: two LU solves and the Schur complement.  Iterative:
        one GMRES on the bordered system, right-preconditioned by the block
        factorisation with J replaced by its sparse LU (y = LU^-1 col once,
        then x = LU^-1 r - t y, t = (row . LU^-1 r - s)/(row . y)); half the
        GMRES work of solving for the two right-hand sides separately."""
        if self.dense:
            z1, z2 = self.solve(rhs), self.solve(col)
            t = (row @ z1 - rhs_row) / (row @ z2)
            return z1 - t * z2, t
        n = self.idx.size
        pre = {}

        def setup():
            pre["y"] = self.lu.solve(col)
            pre["ry"] = row @ pre["y"]

        def prec(v):
            z = self.lu.solve(v[:n])
            t = (row @ z - v[n]) / pre["ry"]
            out = np.empty(n + 1)
            out[:n] = z - t * pre["y"]
            out[n] = t
            return out

        def mv(v):
            out = np.empty(n + 1)
            out[:n] = self.op.matvec(v[:n]) + col * v[n]
            out[n] = row @ v[:n]
            return out

        op = spla.LinearOperator((n + 1, n + 1), matvec=mv, dtype=float)
        M = spla.LinearOperator((n + 1, n + 1), matvec=prec, dtype=float)
        count = [0]

        def cb(_):
            count[0] += 1

        b = np.concatenate([rhs, [rhs_row]])
        setup()
        x0 = None
        if not self.refactored:
            # a factorisation kept from an earlier step: if GMRES needs more
            # than precond_refresh iterations with it (the Jacobian has moved:
            # measured 299 iterations at 257 x 257), refactorise and go on
            x0, info = spla.gmres(op, b, M=M, rtol=self.rtol, atol=0.0, restart=self.P.o.precond_refresh,
                                  maxiter=1, callback=cb, callback_type="pr_norm")
            if info != 0:
                self._factorise()
                setup()
        if x0 is None or info != 0:
            x, info = spla.gmres(op, b, x0=x0, M=M, rtol=self.rtol, atol=0.0, restart=60, maxiter=10, callback=cb,
                                 callback_type="pr_norm")
        else:
            x = x0
        self.gmres_iters += count[0]
        self.last_iters = count[0]
        if info != 0:
            log.debug("EHL GMRES did not reach rtol %.1e (%d iterations)", self.rtol, count[0])
        return x[:n], x[n]


def _row_scale(P: _Problem, A, D, idx, p_ref=None):
    """s_i = 1/(p_ref max_j |J_ij|), J = A + D K_local: Reynolds residual rows in
    units of the pressure scale ``p_ref`` (default p_Hertz)."""
    Jl = (A + D @ P.K_local())[idx][:, idx]
    rowmax = np.asarray(abs(Jl).max(axis=1).todense()).ravel()
    rowmax = np.maximum(rowmax, 1e-12 * np.max(rowmax))
    return 1.0 / ((P.ph if p_ref is None else p_ref) * rowmax)


def _largest_negative_multiplier(P: _Problem, A, D, R, cav, p_ref):
    """Largest negative Reynolds multiplier of the cavitated nodes, in units of ``p_ref``:
    max_i (-s_i R_i) over cavitated i with R_i < 0 (0 if none), s_i = 1/(p_ref max_j |J_ij|) the
    row scale of :func:`_row_scale` taken over the whole row.  A cavitated node whose scaled
    multiplier is below -rtol would gain about that pressure if released; one within
    [-rtol, 0) is a degenerate node (p = R = 0 up to round-off) whose release changes
    nothing the tolerance can see, so it does not block convergence."""
    neg = np.flatnonzero(cav & (R < 0))
    if neg.size == 0:
        return 0.0
    rows = sp.csr_matrix(A)[neg] + sp.csr_matrix(D)[neg] @ P.K_local()  # only the rows asked for
    rowmax = np.asarray(abs(rows).max(axis=1).todense()).ravel()
    return float(np.max(-R[neg] / (p_ref * np.maximum(rowmax, 1e-300))))


def _fb(a, b):
    """Fischer-Burmeister function phi(a, b) = sqrt(a^2 + b^2) - a - b and its
    partial derivatives (phi = 0 <=> a >= 0, b >= 0, a b = 0).  At a = b = 0
    (where phi is not differentiable) the element (1/sqrt2 - 1, 1/sqrt2 - 1)
    of the generalised Jacobian is taken."""
    r = np.hypot(a, b)
    safe = np.where(r > 0, r, 1.0)
    da = np.where(r > 0, a / safe, 2**-0.5) - 1.0
    db = np.where(r > 0, b / safe, 2**-0.5) - 1.0
    return r - a - b, da, db


def _fb_newton(P: _Problem, p, h00, W, max_iter=None, rtol=None, max_damped=None):
    """Semismooth (Fischer-Burmeister) Newton on the coupled system, globalised by an Armijo line search.

    Unknowns: the interior pressures and, with a load, h00.  Equations::

        Phi_i = phi(p_i / p_H, s_i R_i(p, h00)) = 0        (every interior node)
        (int p dA - W) / W = 0                              (load balance)

    phi the Fischer-Burmeister function (:func:`_fb`): Phi_i = 0 is exactly the
    complementarity p_i >= 0, R_i >= 0, p_i R_i = 0, with no active set to
    guess.  s_i = 1/(p_H max_j |J_ij|) scales residual rows to pressures
    (J = A + D K_local, refreshed every step).  The step solves
    the bordered system as the active-set scheme does (two solves with one
    factorisation, :class:`_FBLinear`); it is capped so that no pressure
    moves by more than ``max_step`` p_H and then halved until the merit
    theta = |Phi|^2 + load error^2 decreases by the Armijo fraction 1e-4
    (at most ``line_search`` halvings; if none decreases, the best trial is
    taken and counted as a stall).

    Convergence test (as for the active-set scheme), on the full Newton step
    before the line search: max|dp| <= rtol p_ref, |dh00| <= rtol b^2/R_x and
    relative load error after the step <= 10 rtol; the step is then taken.  Returns ``(p, h00, history, gmres_iterations)``; p is
    clipped at 0 (it is >= -rtol p_H at convergence).
    """
    options, contact = P.o, P.c
    balance = W is not None
    idx = np.flatnonzero(P.free0)
    wv = P.weights[idx]
    history, gm = [], 0

    def merit(R, pp, hh, s):
        phi = _fb(pp[idx] / ps, s * R[idx])[0]
        le = (P.weights @ pp - W) / W if balance else 0.0
        return phi @ phi + le * le, phi, le

    stalls, nfact, keep, damped = 0, 0, None, 0
    max_iter = options.max_iter if max_iter is None else max_iter
    tol = options.rtol if rtol is None else rtol
    for it in range(1, max_iter + 1):
        _spend(P)
        R, hn, A, D, aux = P.assemble(p, h00)
        # pressure scale: p_Hertz, or the largest pressure where that is smaller
        # (hydrodynamic, nearly rigid contacts: p << p_Hertz of the nominal load)
        pmax = float(np.max(p))
        ps = P.ph if pmax <= 0 else min(P.ph, pmax)
        s = _row_scale(P, A, D, idx, ps)
        phi, da, db = _fb(p[idx] / ps, s * R[idx])
        le = (P.weights @ p - W) / W if balance else 0.0
        theta0 = phi @ phi + le * le
        # inexact Newton: GMRES to rtol min(1e-3, |Phi|) (floored at gmres_rtol);
        # the sparse LU preconditioner is kept from the previous step while
        # GMRES needs fewer than precond_refresh iterations per solve
        eta_k = max(options.gmres_rtol, min(options.gmres_forcing, np.sqrt(theta0)))
        lin = _FBLinear(P, A, D, da / ps, db * s, idx, reuse=keep, rtol=eta_k)
        dp = np.zeros(P.N)
        dh = 0.0
        if balance:
            # bordered step: J dp + c dh = -phi, w . dp / W = -le (h00 in units of b^2/R_x)
            col = (db * s) * (D @ np.ones(P.N))[idx] * P.hscale
            dp[idx], t = lin.solve_bordered(-phi, col, wv / W, -le)
            dh = t * P.hscale
        else:
            dp[idx] = lin.solve(-phi)
        gm += lin.gmres_iters
        if not lin.dense:
            nfact += lin.refactored
            # bordered solves refactorise by themselves when the kept LU has gone stale
            keep = lin.lu if (balance or lin.last_iters < options.precond_refresh) else None
        # convergence on the full (undamped) step, before the line search: at the round-off floor
        # the merit is noise and its Armijo test can halve omega at random, so an omega == 1
        # requirement is a coin toss between machines (tests/test_roundoff.py)
        full_dp = np.max(np.abs(dp)) / ps
        if full_dp <= tol and abs(dh) / P.hscale <= tol:
            p_try, h_try = p + dp, h00 + dh
            load_rel = abs(P.weights @ p_try - W) / W if balance else 0.0
            if load_rel <= max(tol, 1e-10) * 10 and np.all(np.isfinite(p_try)):
                p, h00 = p_try, h_try
                history.append((full_dp, abs(dh) / P.hscale, load_rel, int(np.sum(p[idx] < 1e-6 * ps))))
                P.stop = dict(reason="tolerance met", detail=(
                    f"full Newton step max|dp|/p_ref {full_dp:.1e}, |dh00|/(b^2/R_x) {abs(dh) / P.hscale:.1e} <= "
                    f"rtol {tol:.0e}, load error {load_rel:.1e} <= {max(tol, 1e-10) * 10:.0e} after {it} "
                    f"iterations ({stalls} line-search stalls)"))
                log.debug("EHL FB %d: full step |dp|/p_ref = %.2e, dh00/hs = %.2e, load err %.2e: converged",
                          it, full_dp, history[-1][1], load_rel)
                break
        omega = omega_cap = 1.0 / max(np.max(np.abs(dp)) / (options.max_step * ps), 1.0)
        if log.isEnabledFor(logging.DEBUG):
            i = int(np.argmax(np.abs(dp)))
            j = int(np.searchsorted(idx, i))
            loc = P.basis.doflocs[:, i]
            log.debug("EHL FB %d: largest step %.2e p_ref at x/b = %.3f%s (p/p_ref %.3f, s R %.2e, h/hs %.3e)", it,
                      dp[i] / ps, loc[0] / P.bx, "" if contact.is_line else f", y/b = {loc[1] / P.by:.3f}",
                      p[i] / ps, (s * R[idx])[j] if j < idx.size and idx[j] == i else 0.0, hn[i] / P.hscale)
        best = None
        for _ in range(options.line_search + 1):
            trial_p, trial_h = p + omega * dp, h00 + omega * dh
            Rt = P.assemble(trial_p, trial_h, jac=False)[0]
            theta = merit(Rt, trial_p, trial_h, s)[0]
            if best is None or theta < best[0]:
                best = (theta, omega)
            if theta <= (1.0 - 2e-4 * omega) * theta0:
                break
            omega *= 0.5
        else:
            omega = best[1]
        # a stall: no Armijo decrease, or one only after 6 or more halvings
        if omega <= omega_cap / 64:
            stalls += 1
            if stalls >= options.max_stalls:
                err = ConvergenceError(
                    f"EHL Newton line search stalled {stalls} times at M = {contact.moes_M:.4g}, "
                    f"L = {contact.moes_L:.4g} ({P.N} nodes; merit {theta0:.2e}; EHLOptions.max_stalls)")
                err.iterate = (np.maximum(p + omega * dp, 0.0), h00 + omega * dh)
                err.stop = dict(reason="line search stalled", detail=str(err))
                raise err
        damped += omega < 1.0
        if max_damped is not None and damped > max_damped:
            err = ConvergenceError(
                f"EHL Newton needed more than {max_damped} damped steps at M = {contact.moes_M:.4g}, "
                f"L = {contact.moes_L:.4g} ({P.N} nodes; EHLOptions.max_damped)")
            err.iterate = (np.maximum(p, 0.0), h00)
            err.stop = dict(reason="damped-step budget", detail=str(err))
            raise err
        p = p + omega * dp
        h00 = h00 + omega * dh
        pmax = float(np.max(p))
        dmax = omega * np.max(np.abs(dp)) / (P.ph if pmax <= 0 else min(P.ph, pmax))
        load_rel = abs(P.weights @ p - W) / W if balance else 0.0
        history.append((dmax, omega * abs(dh) / P.hscale, load_rel, int(np.sum(p[idx] < 1e-6 * ps))))
        log.debug("EHL FB %d: |dp|/ph = %.2e, dh00/hs = %.2e, load err %.2e, omega %.3g, merit %.2e, gmres %d, "
                  "h_min/hs %.2e, h00/hs %.3g",
                  it, dmax, history[-1][1], load_rel, omega, theta0, lin.gmres_iters, np.min(hn) / P.hscale,
                  h00 / P.hscale)
        if not np.all(np.isfinite(p)):
            raise _stopped("non-finite pressure",
                           f"EHL Newton iteration {it}: non-finite pressure (M = {contact.moes_M:.4g})")
    else:
        err = ConvergenceError(
            f"EHL solve did not converge in {max_iter} Newton iterations at M = {contact.moes_M:.4g}, "
            f"L = {contact.moes_L:.4g}: last |dp|/p_Hertz = {history[-1][0]:.2e}, load error {history[-1][2]:.2e} "
            f"({stalls} line-search stalls; solver.max_iter)"
        )
        err.iterate = (np.maximum(p, 0.0), h00)
        err.stop = dict(reason="iteration limit", detail=str(err))
        raise err
    P.factorisations = nfact
    return np.maximum(p, 0.0), h00, history, gm


def solve_ehl(contact: EHLContact, grid: EHLGrid = EHLGrid(), options: EHLOptions = EHLOptions(),
              initial=None, sequence: bool = True, _final: bool = True, _stage_info=None) -> EHLSolution:
    """Solve an EHL contact; see the module docstring for the method.

    With ``sequence=True`` (default) and no ``initial``, grids finer than 129
    (line) or 33 (point contact) nodes along x are reached by nested iteration: the contact is solved on
    the grid with (nx - 1)/2 + 1 nodes first (recursively) and its pressure,
    interpolated, starts the Newton iteration on the finer grid.  This is what
    makes heavily loaded contacts converge on fine grids (measured: M = 100,
    L = 10 line contact on 513 nodes fails from the Hertz start and converges
    from the 257-node solution).
    """
    from threadpoolctl import threadpool_limits

    outer = _BUDGET.get()
    token = None
    if outer is None:  # the outermost call owns the budget; nested calls (a map's points) spend their own
        limit = options.max_work if options.max_work is not None else \
            DEFAULT_MAX_WORK["line" if contact.is_line else "point"]
        token = _BUDGET.set(dict(limit=limit, spent=0.0, nodes=_grid_nodes(contact, grid)))
    try:
        with threadpool_limits(limits=1, user_api="blas"):
            sol = _solve_ehl(contact, grid, options, initial, sequence, _final, _stage_info)
        if token is not None:
            sol.info["work"] = _BUDGET.get()["spent"]
    except ConvergenceError as exc:
        if token is not None:  # the work this failure took, next to its reason
            exc.stop = dict(getattr(exc, "stop", None) or dict(reason="not converged", detail=str(exc)),
                            work=_BUDGET.get()["spent"])
        raise
    finally:
        if token is not None:
            _BUDGET.reset(token)
    if _final:
        check_solution(sol)
    return sol


# ---------------------------------------------------------------- work budget
_BUDGET = contextvars.ContextVar("ehl_work_budget", default=None)
# Default EHLOptions.max_work, about 2.5 times the most work measured to converge (Newton steps on
# the requested grid, all starts and fallbacks): points 40.5 (M = 1000, L = 10, 129 x 129; M = 20:
# 37.5, through the fallback chain; the bundled ball case 13.9), lines 142.7 (M = 20, L = 10 on 1025
# nodes, through the fallback; the bundled roller slice 40.3).  A line step is cheap (dense LU; 1025
# nodes: 0.01 s), a point step on 129 x 129 is 1.5 - 3.5 s.
DEFAULT_MAX_WORK = {"point": 100.0, "line": 400.0}


def _grid_nodes(contact, grid):
    if contact.is_line:
        return grid.nx
    return grid.nx * (grid.ny or grid.nx)


def _spend(P: _Problem):
    """Count one Newton step of ``P`` in work units (steps on the requested grid: a step on a grid
    of n nodes costs n/N of one on the N-node grid asked for) and stop the whole solve, every start
    and fallback included, when ``EHLOptions.max_work`` is spent."""
    budget = _BUDGET.get()
    if budget is None:
        return
    budget["spent"] += P.N / budget["nodes"]
    if budget["limit"] is not None and budget["spent"] > budget["limit"]:
        c = P.c
        err = ConvergenceError(
            f"EHL solve at M = {c.moes_M:.4g}, L = {c.moes_L:.4g} stopped: its work budget of "
            f"{budget['limit']:g} Newton steps on the requested grid (EHLOptions.max_work, every start and "
            f"fallback counted) is spent, on a {P.shape[0]}-node level; the Newton methods do not converge "
            "here in that work: " + ("use solver.method = 'multigrid' (point contacts) or a lower load"
                                     if not c.is_line else "use a finer grid or a lower load"))
        err.budget = True
        err.stop = dict(reason="work budget", detail=str(err))
        raise err


# ---------------------------------------------------------------- a-posteriori checks
# Thresholds, from the sweep recorded in tests/test_ehl_limits.py (Moes M = 10 ... 1000 (2000 for
# the multigrid), L = 5, 10, 20; line contacts on 129 ... 1025 nodes with the active set, circular
# contacts on 65 ... 257 nodes with the multigrid):
# - FORMULA_TOLERANCE: converged solutions (1025 line nodes; 257 x 257 multigrid up to M = 200)
#   lie within -5.6 % ... +5.4 % of Moes' line and Nijenbanning's point formula (the fits' own
#   scatter: "a few per cent", "within about 5 %"); the wrong answers of issue 20 are +86 % (line,
#   257 nodes, M = 1000) and -35 % (multigrid, 129 x 129, M = 1000).  10 %: twice the scatter.
# - COARSE_TOLERANCE: the discretisation error estimated from the one-level-coarser solution,
#   |h_c - h_c,coarse|/((2^2 - 1) h_c) (second order).  Multigrid cases within 5 % of the formula
#   reach 10.8 % (M = 1000, L = 20, 257 x 257, -4.4 %); those more than 10 % off start at 15.5 %
#   (M = 100, L = 10, 65 x 65, -11.6 %).  13 % lies between.
#   The Newton methods' nested levels (points, 65 x 65 from 33 x 33, M = 20 ... 500, L = 5, 10)
#   reach 10.4 % (M = 500, L = 10, +1.7 % off the formula).  A coarse level whose film went to or
#   below zero (or that did not converge) is outside the asymptotic range: no estimate.
# - multigrid only: an FMG coarser level whose film went to zero or below marks a grid at its
#   resolution limit: every such case of the sweep was 8 % ... 46 % off the formula (M = 1000,
#   L = 10, 257 x 257: -8.4 %).  (The Newton methods' floored film is not such a sign: M = 500,
#   L = 10 on 65 x 65 is +1.7 % off with a 33 x 33 level at -6.8e-8 m.)
FORMULA_TOLERANCE = 0.10
COARSE_TOLERANCE = 0.13
# where the closed forms were compared with converged solutions (Barus, incompressible, Newtonian):
FORMULA_ENVELOPE = dict(M=(10.0, 2000.0), L=(5.0, 20.0))


def closed_form_central_film(contact: EHLContact):
    """``(name, h_c [m])`` of the closed-form central film this project checks ``contact`` against,
    or None outside the conditions it was fitted and measured for: a Barus, incompressible,
    Newtonian lubricant, given load, a line or circular contact, and Moes' M and L inside
    :data:`FORMULA_ENVELOPE` (Moes' line formula; Nijenbanning-Venner-Moes for circles)."""
    from .laws.film import moes_line_central, nijenbanning_central
    from .laws.lubricant import Barus, Incompressible

    lub = contact.lubricant
    if (contact.load is None or lub.eyring_stress is not None or not isinstance(lub.viscosity, Barus)
            or not isinstance(lub.density, Incompressible) or contact.squeeze_velocity != 0.0):
        return None
    if not contact.is_line and contact.radius_y != contact.radius_x:
        return None
    M, L = contact.moes_M, contact.moes_L
    (m0, m1), (l0, l1) = FORMULA_ENVELOPE["M"], FORMULA_ENVELOPE["L"]
    if not (m0 <= M <= m1 and l0 <= L <= l1):
        return None
    scale = contact.radius_x * np.sqrt(2 * contact.U)
    if contact.is_line:
        return "Moes' line formula", float(moes_line_central(M, L) * scale)
    return "Nijenbanning-Venner-Moes", float(nijenbanning_central(M, L) * scale)


def _finer(nx, times=1):
    for _ in range(times):
        nx = 2 * (nx - 1) + 1
    return nx


def check_solution(sol: EHLSolution) -> list[str]:
    """A-posteriori checks of a converged EHL solution: its central film against the closed form
    (:func:`closed_form_central_film`, beyond :data:`FORMULA_TOLERANCE`) and against the
    one-level-coarser solution that nested iteration (Newton) or the FMG start (multigrid) computed
    (estimated discretisation error beyond :data:`COARSE_TOLERANCE`; multigrid: or a coarse film <= 0).

    Each failed check is one line naming the figures and the grid needed; they are logged (WARNING)
    and listed in ``sol.info["warnings"]``, or, with ``EHLOptions(strict=True)``, raised as
    :class:`~lubrication.errors.ConvergenceError`.  Returns the list (empty: nothing to report).
    """
    c, P, info = sol.contact, sol.problem, sol.info
    nx = int(P.shape[0])
    grid = f"{nx} nodes" if c.is_line else f"{P.shape[0]} x {P.shape[1]} nodes"
    hc = sol.central_film_thickness
    checks, out = {}, []
    ref = closed_form_central_film(c)
    if ref is not None:
        name, href = ref
        dev = hc / href - 1.0
        checks["closed_form"] = dict(formula=name, central_film=href, deviation=dev, tolerance=FORMULA_TOLERANCE)
        if abs(dev) > FORMULA_TOLERANCE:
            out.append(f"EHL central film {hc:.4g} m on {grid} at M = {c.moes_M:.4g}, L = {c.moes_L:.4g} is {dev:+.0%} "
                       f"off {name} ({href:.4g} m; converged solutions lie within 6 % of it): the grid does not "
                       f"resolve the contact; use grid.nx >= {_finer(nx)}")
    coarse = info.get("coarse_level")
    if coarse is not None and np.isfinite(coarse.get("central_film", np.nan)):
        hcc, hmc = coarse["central_film"], coarse["minimum_film"]
        est = abs(hc - hcc) / (3.0 * abs(hc))
        checks["coarse_level"] = dict(coarse, estimated_error=est, tolerance=COARSE_TOLERANCE)
        collapsed = hmc <= 0.0 or hcc <= 0.0
        if collapsed and info.get("method") == "multigrid":
            out.append(f"EHL solution on {grid} at M = {c.moes_M:.4g}, L = {c.moes_L:.4g}: the one-level-coarser "
                       f"FMG grid ({coarse['nx']} nodes along x) has a collapsed film (minimum {hmc:.3g} m), so this "
                       f"grid is at its resolution limit (central film {hc:.4g} m against {hcc:.4g} m there); use "
                       f"grid.nx >= {_finer(nx)}")
        elif not collapsed and coarse.get("converged", True) and est > COARSE_TOLERANCE:
            # second order: the error falls 4 times per halving of the cells
            k = int(np.ceil(np.log(est / COARSE_TOLERANCE) / np.log(4.0)))
            out.append(f"EHL central film {hc:.4g} m on {grid} differs by {abs(hc / hcc - 1):.0%} from the "
                       f"one-level-coarser grid's {hcc:.4g} m (estimated discretisation error {est:.0%} > "
                       f"{COARSE_TOLERANCE:.0%}) at M = {c.moes_M:.4g}, L = {c.moes_L:.4g}; use grid.nx >= "
                       f"{_finer(nx, max(k, 1))}")
    info["checks"] = checks
    info["warnings"] = list(out)
    if out and P.o.strict:
        err = ConvergenceError("; ".join(out) + " (EHLOptions.strict)")
        err.stop = dict(reason="a-posteriori check failed", detail="; ".join(out))
        raise err
    for text in out:
        log.warning("%s", text)
    return out


def _solve_ehl(contact, grid, options, initial=None, sequence=True, _final=True, _stage_info=None, _coarse=False,
               _loose=False, _fallback=True):
    """:func:`solve_ehl` body (BLAS limited to one thread by the caller: the
    dense LU of a 561-unknown contact took 0.18 s with two OpenBLAS threads
    and 0.004 s with one on this project's 2-core machine)."""
    t0 = time.perf_counter()
    if options.method == "multigrid":
        return _solve_multigrid(contact, grid, options, initial)
    if not contact.is_line and grid.nx > options.max_point_grid:
        raise InputError(
            f"grid.nx = {grid.nx} for a point contact: point contacts are solved up to {options.max_point_grid} "
            f"nodes per side by the Newton methods (lubrication.ehl.EHLOptions.max_point_grid: the largest grid measured to converge, "
            f"M = 100, L = 10; a Newton step costs about 5 s of one core on 257 x 257 and the sparse-LU "
            f"preconditioner's fill grows faster than the grid); use nx <= {options.max_point_grid}, or "
            f"solver.method = 'multigrid'"
        )
    coarsest = 129 if contact.is_line else 33
    nests = initial is None and sequence and grid.nx > coarsest and (grid.nx - 1) % 2 == 0
    first_start = options.first_order_start
    if first_start == "auto":
        # points finer than 129 x 129: every grid (measured on 257 x 257, M =
        # 100 and 200: the second-order iteration from the prolonged
        # second-order solution never converged, every step damped)
        first_start = "every_grid" if (contact.is_line or grid.nx > 129) else "coarsest"
    if options.consistent_supg and _stage_info is None and not (nests and first_start == "coarsest"):
        # defect-correction start: the first-order (plain SUPG) solution on the
        # same grid starts the second-order Newton iteration; started from a
        # Hertz or prolonged pressure, the second-order scheme alone stalls on
        # 2-D grids (measured: M = 20, L = 10 on 65 x 65 nodes)
        import dataclasses

        try:
            first = _solve_ehl(contact, grid, dataclasses.replace(options, consistent_supg=False), initial=initial,
                               sequence=sequence, _final=False, _coarse=_coarse, _loose=True)
            out = _solve_ehl(contact, grid, options, initial=first, sequence=False, _final=_final, _coarse=_coarse,
                             _stage_info=dict(first_order_iterations=first.info["iterations"],
                                              first_order_central_film=first.central_film_thickness,
                                              first_order_time=first.info["wall_time"]))
        except ConvergenceError as exc:
            if getattr(exc, "budget", False):  # the work budget is spent: no fallback
                raise
            if not (_fallback and not _coarse and nests and options.first_order_start == "auto"):
                raise
            # the second-order iteration from the first-order solution of the
            # same grid failed: the other start, second order from the
            # prolonged coarse second-order solution (measured need: line
            # contact M = 20, L = 10 on 1025 nodes, where the outlet-spike node
            # oscillates from the first-order start and 15 steps converge from
            # the 513-node solution)
            log.info("EHL: %s; retrying from the prolonged second-order solution on %d nodes", exc, grid.nx)
            try:
                out = _solve_ehl(contact, grid, dataclasses.replace(options, first_order_start="coarsest"),
                                 sequence=sequence, _final=_final, _fallback=False)
            except ConvergenceError as exc2:
                if getattr(exc2, "budget", False):
                    raise
                err = ConvergenceError(f"{exc2}; before that, from the first-order start: {exc}")
                err.stop = getattr(exc2, "stop", None)
                raise err from exc2
            out.info["fallback"] = dict(failed_start=str(exc))
        out.info["wall_time"] = time.perf_counter() - t0
        return out
    P = _Problem(contact, grid, options)
    if nests:
        coarse_grid = EHLGrid(nx=(grid.nx - 1) // 2 + 1, ny=None if grid.ny is None else (grid.ny - 1) // 2 + 1,
                              x_min=grid.x_min, x_max=grid.x_max, y_max=grid.y_max)
        try:
            coarse = _solve_ehl(contact, coarse_grid, options, sequence=True, _final=False, _coarse=True)
        except ConvergenceError as exc:
            if getattr(exc, "budget", False):  # the work budget is spent: no fallback
                raise
            # a coarse level is only a start: where it cannot resolve the
            # outlet constriction (heavy loads), its last iterate still is one
            if getattr(exc, "partial", None) is None:
                raise
            log.info("EHL coarse level %s did not converge (%s); its last iterate starts %d nodes",
                     coarse_grid.nx, exc, P.N)
            coarse = exc.partial
        Pc = coarse.problem
        coarse_hn = Pc.film(coarse.pressure, coarse.h00)
        # the coarser level's films, for the a-posteriori check (check_solution)
        coarse_level = dict(nx=int(Pc.shape[0]), central_film=float(coarse_hn[np.argmin(np.linalg.norm(
            Pc.basis.doflocs, axis=0))]), minimum_film=float(np.min(coarse_hn)),
            converged=coarse.film_thickness is not None)
        initial = EHLSolution(contact, P, _prolong(coarse, P), None, coarse.h00,
                              dict(coarse_iterations=coarse.info.get("iterations")))
    balance = contact.load is not None
    W = contact.load if balance else None
    if not nests:
        coarse_level = None
    if initial is not None and initial.pressure.shape == (P.N,):
        p, h00 = initial.pressure.copy(), float(initial.h00)
    elif initial is not None and getattr(initial, "problem", None) is not None:
        # a solution on another grid (other nx or inlet): its pressure
        # interpolated (multilinear, 0 outside its domain) onto this grid
        p, h00 = _prolong(initial, P), float(initial.h00)
    else:
        p = _hertz_guess(P)
        if not balance:
            p *= 0.0
        hc = _film_guess(contact)
        h00 = contact.approach if not balance else hc - float(P.deflect(p)[np.argmin(np.abs(P.rigid))])
    if not balance:
        h00 = contact.approach
    p[P.fixed] = 0.0
    method = options.method
    if method == "auto":
        method = "active_set" if contact.is_line else "fischer_burmeister"
    newton = _fb_newton if method == "fischer_burmeister" else _active_set_newton
    budget = {}
    if method == "fischer_burmeister":
        if _coarse:
            budget["max_iter"] = options.coarse_max_iter
        if _coarse or _loose:
            # a start for the next stage: converged to coarse_rtol, well below
            # the change the next grid (or scheme) makes (measured: max|dp| of
            # 0.2 - 0.5 p_Hertz at the outlet spike from 65 to 129 and 129 to 257)
            budget["rtol"] = max(options.rtol, options.coarse_rtol)
        elif options.consistent_supg and _stage_info is None and nests:
            # second order from the prolonged coarse solution: where it
            # wanders (damped steps at the outlet spike: measured on 257 x 257,
            # every step damped, |dp| capped at the spike), fall back early
            budget["max_damped"] = options.max_damped
    try:
        p, h00, history, gm = newton(P, p.copy(), h00, W, **budget)
    except ConvergenceError as exc:
        if getattr(exc, "budget", False):  # the work budget is spent: no fallback
            raise
        if _coarse and getattr(exc, "iterate", None) is not None:
            exc.partial = EHLSolution(contact, P, exc.iterate[0], None, exc.iterate[1], {})
        if _coarse or not (options.consistent_supg and _stage_info is None and nests and _fallback):
            raise
        # second order from the prolonged coarse solution failed: the full
        # defect-correction chain instead (first-order nested iteration from
        # the coarsest grid, then second order on this grid); measured need:
        # M = 20, L = 10 on 129 x 129 (the second-order iteration from the
        # 65 x 65 solution wanders into an oscillating outlet spike)
        import dataclasses

        log.info("EHL: %s; retrying with first-order nested iteration on %d nodes", exc, P.N)
        out = _solve_ehl(contact, grid, dataclasses.replace(options, first_order_start="every_grid"),
                         sequence=True, _final=_final, _coarse=_coarse)
        out.info["fallback"] = dict(failed_start=str(exc))
        out.info["wall_time"] = time.perf_counter() - t0
        return out
    hn = P.film(p, h00)
    if _final and np.min(hn) <= options.h_floor * P.hscale * 1.0001:
        raise _stopped("film collapsed",
            f"EHL solution touches the film-thickness floor ({options.h_floor:g} of b^2/R_x): the film "
            f"has collapsed at M = {contact.moes_M:.4g}; refine the grid or reduce the load"
        )
    dense = P.N <= (options.dense_max_line if contact.is_line else options.dense_max)
    linear = "dense LU" if dense else ("GMRES + ILU" if method == "active_set" else "GMRES + sparse LU (local K)")
    info = dict(iterations=len(history), history=history, wall_time=time.perf_counter() - t0,
                gmres_iterations=gm, unknowns=int(P.N), linear=linear, method=method,
                scheme="second order" if options.consistent_supg else "first order", **(_stage_info or {}))
    info.update(stop_reason=P.stop["reason"], stop_detail=P.stop["detail"])
    if coarse_level is not None:
        info["coarse_level"] = coarse_level
    log.info("EHL M=%.4g L=%.4g: %d unknowns, %d Newton iterations, %.2f s", contact.moes_M, contact.moes_L,
             P.N, len(history), info["wall_time"])
    return EHLSolution(contact, P, p, hn, h00, info)


def multigrid_grid(contact: EHLContact, grid: EHLGrid, coarsest_cells: int = 16) -> EHLGrid:
    """The grid that ``method="multigrid"`` solves on: ``grid`` with ``ny``
    chosen (if not given) so that both cell counts halve down to the coarsest
    grid (``coarsest_cells`` cells along x).  nx must be coarsest_cells 2^k + 1
    (17, 33, 65, 129, 257, 513, 1025 by default)."""
    if contact.is_line:
        raise InputError("solver.method = 'multigrid' solves point contacts; line contacts use 'auto' "
                         "(active set) or 'fischer_burmeister'")
    if contact.lubricant.eyring_stress is not None:
        raise InputError(f"lubricant.eyring_stress = {contact.lubricant.eyring_stress!r}: solver.method = 'multigrid' "
                         "is Newtonian; use 'auto', 'fischer_burmeister' or 'active_set' for Eyring flow")
    cells = grid.nx - 1
    k = 0
    while cells % 2 == 0 and cells // 2 >= coarsest_cells:
        cells //= 2
        k += 1
    if cells != coarsest_cells:
        allowed = ", ".join(str(coarsest_cells * 2**i + 1) for i in range(7))
        raise InputError(f"grid.nx = {grid.nx} for solver.method = 'multigrid': nx - 1 must be {coarsest_cells} "
                         f"times a power of 2 (the coarsest grid has {coarsest_cells} cells); use one of {allowed}")
    step = 2**k
    if grid.ny is not None:
        if (grid.ny - 1) % step or (grid.ny - 1) // step < 4:
            raise InputError(f"grid.ny = {grid.ny} for solver.method = 'multigrid' with nx = {grid.nx}: ny - 1 must be "
                             f"a multiple of {step} and at least {4 * step}")
        return grid
    hp = hertz.point_contact(contact.hertz_load(), contact.radius_x, contact.radius_y, contact.e_star)
    bx, by = (hp.b, hp.a) if contact.radius_y >= contact.radius_x else (hp.a, hp.b)
    cy = (grid.nx - 1) * 2 * grid.y_max * by / ((grid.x_max - grid.x_min) * bx)
    ny = max(4, int(round(cy / step))) * step + 1
    import dataclasses

    return dataclasses.replace(grid, ny=ny)


def _solve_multigrid(contact: EHLContact, grid: EHLGrid, options: EHLOptions, initial=None) -> EHLSolution:
    """``method="multigrid"``: FAS multigrid (:mod:`lubrication.ehl_multigrid`) on the
    nodes of :class:`_Problem` (same grid, kernel, film and outputs as the Newton
    methods).  Steady point contacts, given load or approach."""
    from .ehl_multigrid import MultigridEHL, MultigridOptions

    t0, c0 = time.perf_counter(), time.process_time()
    mopt = options.multigrid if options.multigrid is not None else MultigridOptions()
    if contact.squeeze_velocity != 0.0:
        raise InputError(f"squeeze_velocity = {contact.squeeze_velocity!r} with solver.method = 'multigrid': the "
                         "multigrid solver is steady; use the Newton methods (solver.method = 'auto') for squeeze")
    g = multigrid_grid(contact, grid, mopt.coarsest_cells)
    P = _Problem(contact, g, options)
    P.uniform_weights()  # load and outputs without the FEM assembly templates
    t_setup = time.perf_counter() - t0
    if contact.load is not None:
        if initial is not None and getattr(initial, "h00", None) is not None:
            h00 = float(initial.h00)
        else:
            p = _hertz_guess(P)
            h00 = _film_guess(contact) - float(P.deflect(p)[np.argmin(np.abs(P.rigid))])
    else:
        h00 = contact.approach
    mg = MultigridEHL(P, contact, mopt)
    Pg, H00, history = mg.solve(h00 / P.hscale)
    p = P.ph * Pg.ravel()[P.flat]
    h00 = H00 * P.hscale
    hn = P.film(p, h00)
    if np.min(hn) <= 0.0:
        raise _stopped("film collapsed",
            f"EHL multigrid solution at M = {contact.moes_M:.4g}, L = {contact.moes_L:.4g} on {g.nx} x {g.ny} "
            f"nodes has a film thickness <= 0 (min {np.min(hn) / P.hscale:.3g} b^2/R_x): the grid does not "
            "resolve the outlet constriction; refine the grid")
    info = dict(iterations=len(history) - 1, cycles=len(history) - 1, history=history,
                work_units=float(mg.work), wall_time=time.perf_counter() - t0, cpu_time=time.process_time() - c0,
                setup_time=t_setup, unknowns=int(P.N), levels=[lv.shape for lv in mg.levels], method="multigrid",
                scheme=f"finite differences, order-{mopt.order} upstream wedge", linear="line relaxation (FAS)",
                residual=history[-1]["residual"], load_error=history[-1]["load_error"],
                stop_reason="tolerance met", stop_detail=f"{history[-1].get('stop')} stop: "
                f"{history[-1].get('stop_detail', '')} after {len(history) - 1} cycles")
    coarse = history[0].get("coarse")
    if coarse is not None:  # the FMG solution of the next-coarser grid (check_solution)
        info["coarse_level"] = dict(nx=int(mg.levels[-2].shape[0]), central_film=coarse["H_centre"] * P.hscale,
                                    minimum_film=coarse["H_min"] * P.hscale, converged=True)
    log.info("EHL multigrid M=%.4g L=%.4g: %d x %d nodes, %d cycles, %.1f work units, %.2f s", contact.moes_M,
             contact.moes_L, g.nx, g.ny, info["cycles"], info["work_units"], info["wall_time"])
    return EHLSolution(contact, P, p, hn, h00, info)


class NormalCoefficients(NamedTuple):
    """Normal film coefficients about a steady state (unpacks as ``K, C, solution``).

    ``stiffness`` K = -dF/dh00 [N/m] and ``damping`` C = -dF/d(dh00/dt)
    [N s/m] (per unit length, [N/m^2] and [N s/m^2], for line contacts),
    F = int p dA the film force that pushes the bodies apart, h00 the
    rigid-body separation (so K = dF/d(delta) for the approach delta =
    -h00); both > 0.  ``solution`` is the steady state; its
    ``info["normal_coefficients"]`` holds the method and its details.
    """

    stiffness: float
    damping: float
    solution: EHLSolution


def ehl_normal_coefficients(contact: EHLContact, grid: EHLGrid = EHLGrid(nx=33),
                            options: EHLOptions = EHLOptions(), method: str = "linearised",
                            rel_step: float = 1e-3, steady: EHLSolution | None = None) -> NormalCoefficients:
    r"""Normal stiffness and damping of an EHL film about its steady state.

    The steady state is ``contact`` solved with its load (or taken from
    ``steady``, solved on ``grid`` with ``options``).  Then, with the
    discrete system R(p, h00, hdot) = 0 (Reynolds with the squeeze source
    rho hdot, hdot = dh00/dt; elasticity inside h) and F = w . p:

    ``method="linearised"`` (default, one extra factorisation): on the nodes
    that carry pressure (the cavitated set held fixed: at the Reynolds
    free boundary p and grad p vanish, so to first order the load does not
    depend on where the boundary moves)::

        (A + D K) dp/dh00 = -dR/dh00 = -D 1,   (A + D K) dp/dhdot = -dR/dhdot
        dR_i/dhdot = int rho phi_i dA + int tau rho (u_m . grad phi_i) dA     (SUPG part)
        K = -w . dp/dh00,   C = -w . dp/dhdot

    ``method="finite_difference"``: four prescribed-approach solves on the
    same grid (``scale_load`` = the steady load), started from the steady
    pressure: central differences in h00 (step ``rel_step`` h_c) and in
    dh00/dt (step ``rel_step`` u_m h_c / b_x).

    Parameters
    ----------
    contact : EHLContact
        With ``load`` given (the steady state).
    grid, options : EHLGrid, EHLOptions
        Moderate grids are meant (33 x 33 points, 257 line nodes: well under a
        second each for the linearised method here).
    method : {"linearised", "finite_difference"}
    rel_step : float
        Relative finite-difference step.
    steady : EHLSolution, optional
        A converged steady state of ``contact`` on ``grid`` (skips its solve).

    Returns
    -------
    NormalCoefficients
        ``(K, C, steady_solution)``.

    Examples
    --------
    >>> K, C, s = ehl_normal_coefficients(EHLContact.from_moes(100, 10, line=True), EHLGrid(nx=257))
    >>> bool(K > 0 and C > 0)
    True
    """
    import dataclasses

    from threadpoolctl import threadpool_limits

    methods = ("linearised", "finite_difference")
    if method not in methods:
        raise unknown_choice("normal coefficients method", method, methods)
    if contact.load is None:
        raise InputError("ehl_normal_coefficients needs a contact with 'load' (the steady state), not 'approach'")
    if options.method == "multigrid":
        raise InputError("solver.method = 'multigrid' for normal coefficients: the multigrid solver is steady and has "
                         "no Jacobian; use solver.method = 'auto' (Newton) for stiffness and damping")
    t0 = time.perf_counter()
    sol = steady if steady is not None else solve_ehl(contact, grid, options)
    P = sol.problem
    with threadpool_limits(limits=1, user_api="blas"):
        if method == "linearised":
            p, h00 = sol.pressure, float(sol.h00)
            R, hn, A, D, aux = P.assemble(p, h00)
            # the Reynolds set: interior nodes where the pressure, not the
            # (row-scaled) residual, is the larger member of the complementary pair
            inner = np.flatnonzero(P.free0)
            s_row = _row_scale(P, A, D, inner)
            idx = inner[p[inner] / P.ph > s_row * R[inner]]
            lin = _FBLinear(P, A, D, np.zeros(idx.size), np.ones(idx.size), idx)
            b = P.basis
            dR_dh = D @ np.ones(P.N)
            dR_dv = np.asarray(asm(_source_load, b, g=aux["rho"])) + np.asarray(
                asm(_supg_load, b, t=aux["tau"] * aux["rho"], u=P.u))
            w = P.weights[idx]
            K = -float(w @ lin.solve(-dR_dh[idx]))
            C = -float(w @ lin.solve(-dR_dv[idx]))
            details = dict(method=method, free_nodes=int(idx.size), gmres_iterations=lin.gmres_iters)
        else:
            hc = sol.central_film_thickness
            base = dataclasses.replace(contact, load=None, approach=float(sol.h00), scale_load=contact.load)
            dh = rel_step * hc
            dv = rel_step * contact.mean_speed * hc / P.bx

            def force(**change):
                s2 = _solve_ehl(dataclasses.replace(base, **change), grid, options, initial=sol, sequence=False,
                                _final=False, _stage_info={})
                return s2.load, s2.info["iterations"]

            (fp, ip), (fm, im) = force(approach=sol.h00 + dh), force(approach=sol.h00 - dh)
            (vp, jp), (vm, jm) = (force(squeeze_velocity=contact.squeeze_velocity + dv),
                                  force(squeeze_velocity=contact.squeeze_velocity - dv))
            K = -(fp - fm) / (2 * dh)
            C = -(vp - vm) / (2 * dv)
            details = dict(method=method, h00_step=dh, squeeze_step=dv, newton_iterations=[ip, im, jp, jm])
    details["wall_time"] = time.perf_counter() - t0
    sol.info["normal_coefficients"] = details
    log.info("EHL normal coefficients (%s): K = %.4g, C = %.4g, %.2f s", method, K, C, details["wall_time"])
    return NormalCoefficients(K, C, sol)
