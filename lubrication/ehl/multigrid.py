r"""Multilevel (FAS multigrid) solver of steady EHL point contacts.

The method of Venner & Lubrecht, *Multilevel Methods in Lubrication*
(Elsevier 2000, ch. 6-8), with the elastic deflection on every level by the
FFT (DC-FFT) kernel of :mod:`lubedyn.lubrication.elastic` instead of multilevel
multi-integration (O(N log N) instead of O(N); same influence coefficients).

Equations (dimensionless, X = x/b_x, Y = y/b_x, P = p/p_H, H = h R_x/b_x^2,
b_x the Hertz semi-axis along the entrainment direction x, p_H the Hertz
pressure; rho and eta relative to their ambient values)::

    d/dX(eps dP/dX) + d/dY(eps dP/dY) - d(rho H)/dX = 0,   eps = rho H^3/(eta lambda)
    lambda = 12 u_m eta0 R_x^2/(p_H b_x^3)                 (= (128 pi^3/(3 M^4))^(1/3), circular)
    H = H00 + X^2/2 + (R_x/R_y) Y^2/2 + (p_H R_x/b_x^2) sum_j k_ij P_j
    hx hy sum P = w/(p_H b_x^2)                             (= 2 pi/3, circular)
    P >= 0, r >= 0, P r = 0                                 (r = -L(P): outlet cavitation)

k_ij [m/Pa] are the influence coefficients of :class:`~lubedyn.lubrication.elastic.ElasticKernel`
(uniform pressure on node j's cell, deflection at node i), so the film is
h = h00 + x^2/(2 R_x) + y^2/(2 R_y) + u, the film of :mod:`lubedyn.lubrication.ehl`,
divided by b_x^2/R_x; for a circular contact the elastic term is Venner's
(2/pi^2) int P/r dX'dY'.  The nodes are those of :mod:`lubedyn.lubrication.ehl`
(cell centres of the FFT grid); the discretisation is finite differences:

- Poiseuille term: second-order central differences with eps at the
  half-points eps_{i+1/2} = (eps_i + eps_{i+1})/2;
- wedge term: second-order upstream, (1.5 rhoH_i - 2 rhoH_{i-1} + 0.5
  rhoH_{i-2})/hx (first order on the first interior node), used in the
  relaxation as well (no defect correction was needed; ``order=1`` gives
  first-order upstream throughout).

Relaxation (one sweep, lines along x, j ascending): for every line, the
banded system (3 sub-, 2 super-diagonals) of the line's Newton-like
corrections is solved by band elimination with partial pivoting
(:func:`band_solve`).  Row i is a Gauss-Seidel row where
max(eps_{i+-1/2}/hx^2, eps_{j+-1/2}/hy^2) > ``xi_switch`` (Poiseuille
dominated: change delta_i applied at the node, under-relaxed by
``omega_gs``), else a Jacobi distributive row (change delta_i applied at the
node and -delta_i/4 at its four neighbours, from the pressures before the
sweep, under-relaxed by ``omega_jac``; the row's coefficients are those of
the distributed change: Poiseuille -1.25 sum xi on the diagonal, xi_w +
sum xi/4 and -xi_w/4 on the first and second upstream columns (likewise
downstream), and the distributed influence coefficients K_d - (K_{d-1} +
K_{d+1} + 2 K_{d,1})/4 in the wedge part).  On grids of spacing at most
``gs_ratio_spacing`` (6/256 b_x: 257 nodes along x on the standard domain and
finer) a row whose pressure exceeds ``gs_ratio_pressure`` (0.5 p_H) is
Gauss-Seidel only if, besides, eps varies by less than ``gs_eps_ratio`` (100)
over its five nodes.  Why (issue 42, measured at 513 x 513, M = 20, L = 10):
the cycles converged with an alternating load and H_c error (ratio about -0.6
per cycle; the coarse-grid correction left a load error of 3e-5, the one
post-relaxation moved it to -4e-4), and the largest pressure errors, 0.4-0.9
p_H at single nodes, sat on the outlet spike's flanks (P = 1.6-2.3 p_H) at
Gauss-Seidel rows with eps/h^2 = 0.45-1.7 -- Jacobi rows on 257 x 257, where
eps/h^2 is four times smaller.  There the viscosity's exponential makes eps
vary by orders of magnitude over one node, and a Gauss-Seidel row, which
freezes eps, overshoots.  With the condition the H_c, H_min and load errors
after cycle 2 at 513 x 513 are 4e-5 (M = 20), 2e-5 (50, 100), 2e-4 (200)
instead of 2e-3, 1e-3, 3e-4, 1e-3; at 257 x 257 2e-5 (M = 20), 6e-5 (50),
2e-4 (100) instead of 9e-5, 8e-4, 2e-3.  Without the pressure bound the inlet
rows of heavy loads turned Jacobi too and their last cycles slowed (M = 1000
on 257 x 257: 15 instead of 11 cycles to the residual test); with it M = 500
and 1000 run as before (M = 1000: the same errors cycle by cycle) or faster.
Tried instead: a switch of 3 everywhere (cures M = 20 but slows M >= 200 on
129 x 129 and M >= 500 on finer grids), the ratio condition on every grid
(slows 65 x 65: M = 50 needs 8-9 cycles to 1e-3 instead of 4), nu1 = 2,
nu0 = 40, omega_gs = 0.25 (no cure).  Where one of the line nodes
i-2 .. i+2 is cavitated, only the diagonal is kept (point relaxation).
Cavitation is handled by projection: every updated pressure is max(P, 0)
(projected Gauss-Seidel/Jacobi: a relaxation of the complementarity
problem P >= 0, r >= 0, P r = 0 rather than a Reynolds solve with a guessed
free boundary).  The film (FFT) and eps are recomputed before every sweep
and frozen in it.

Coarse grids (full approximation scheme, standard coarsening down to 16
cells along x): pressure restricted by full weighting (injection where one
of the nine fine nodes is cavitated), residuals by full weighting with zero
residual at cavitated fine nodes, the film by injection with the FAS film
right-hand side (the coarse film equals the injected fine film at the
restricted pressure), the force balance by its FAS right-hand side.  The
coarse correction is interpolated bilinearly and added only where the fine
pressure is positive, then clipped at zero.  H00 is updated on the coarsest
grid only, H00 += h_fact g with g = hx hy sum P - w/(p_H b_x^2) (the coarse
FAS force residual), ``h00_updates`` times per visit, each after
nu0/(h00_updates + 1) relaxations.  FMG start: the Hertz pressure on the
coarsest grid, cubic interpolation to each finer grid, ``fmg_cycles``
cycles per intermediate grid, then cycles on the target grid until
convergence.  Defaults: W(3, 1)-cycles (``gamma=2``, ``nu1=3``), nu0 = 20,
three H00 updates per coarsest visit, h_fact scaled by the contact's dry
Hertz stiffness (Venner's factors are for the circular contact).  Measured
at 257 x 257 (L = 10): V(2, 1)-cycles stall at M = 20 (a two-cycle limit
cycle at the outlet spike, residual 6e-5); W(2, 1) converged for the
circular contacts but not for R_y = 4 R_x on 257 x 641 nodes (a slowly
growing two-cycle oscillation of the spike's Jacobi-distributive rows,
residual 4e-5; lower omega_jac, a smaller h_fact, nu2 = 2 or first-order
coarse grids did not cure it); W(3, 1) converges in 10-17 cycles for all
of them, at about 0.5 residual reduction per cycle.  nu0 = 40 (Venner's
value) gave the same cycles with 10-30 % more time; one H00 update per visit
needed 25 instead of 16 cycles at M = 100 (V-cycles).

Elastic deflection on each level: the DC-FFT product padded to 2n - 2 per
axis (the influence coefficients are even, so the two offsets +-(n-1) that
this length folds together are equal; 512 for 257 nodes, a power of two,
against next_fast_len(2n - 1) = 540 before and 2n = 514, which contains the
prime 257: three times slower; :func:`_level_spectrum`), the real
transforms along y run on the n pressure rows only (:func:`_deflect`;
together several times faster than rfftn on the 540^2 padding at 257 x 257), and a dense
product on grids of at most 600 nodes (the coarsest, where the FFT call overhead dominates; from
33 x 33 on the FFT is faster).

Stopping (target grid, after every cycle, from cycle 2 on).  Error test
(``stop="error"``, the default): the full-multigrid principle (Brandt 1984;
Trottenberg et al. 2001, sec. 2.6): the cycles end when the algebraic error is
at most ``error_fraction`` = 0.5 of the discretisation error, so the answer's
error is at most 1.5 times the grid's own (measured below: at most 1.03
times).  For q = H_c (the node at X = Y = 0) and q = H_min the algebraic error is estimated from the changes
d_k = |q_k - q_{k-1}| of the last two cycles as max(d_k, d_{k-1}/2)
max(1, r/(1 - r)), r = min(d_k/d_{k-1}, 0.9) (the rest of a geometric series,
guarded against a sign change), relative to q; the discretisation error as
max(|q - q_2h|, |q_2h - q_4h|/2^p)/(2^p - 1) relative to q, q_2h and q_4h the
values on the next two coarser grids after their FMG cycles, p = ``order``
(the second term keeps a cancellation between q and q_2h from shrinking the
limit: at 513 x 513, M = 20 it gives 4.1e-4 for H_min where the first gives
2.7e-4).  Where the 2h grid's film has collapsed (H <= 0: M >= 100 on 65 x 65,
M >= 500 on 129 x 129, M = 1000 on 257 x 257) there is no estimate and the
residual test below ends the cycles.  The load is imposed, not discretised:
its relative error must be at most H_c's limit and at most ``load_limit``
(1e-4).  ``error_cap`` (default None) caps the limits (the former default,
min(0.02 x discretisation error, 5e-5), ran 6-17 cycles at 129 x 129 ...
513 x 513, the more the finer the grid).  Residual test (also with the error
test: whichever comes first): the relative projected ("natural") residual res = sum_i |max(P_i + r_i/a_ii,
0) - P_i| / sum_i P_i (a_ii = dL_i/dP_i, including the elastic
self-influence; it vanishes exactly at a complementarity solution and is not
dominated by free-boundary nodes whose pressures flip between 0 and 1e-7, as
sum |r| over P > 0 was) at most ``rtol`` (1e-5) and the relative load error at
most ``load_rtol`` (1e-5); ``stop="residual"`` uses it alone.  The history's
last entry names the rule in ``stop`` with the figures in ``stop_detail``.
Measured by replaying the rule on 26 scenes cycled 20-25 times (M = 20 ...
1000, L = 10, 65^2 ... 513^2, elliptic R_y = 4 R_x, Roelands/Dowson-Higginson;
the rule reads only the history, so the replay is exact), against each
scene's last iterate: wherever the error test stopped, the H_c and H_min
errors were at most 0.06 of their limits (0.028 of the discretisation error),
the load's at most 0.88 of its own (9e-5, 129 x 129); it stopped after cycle 3
(31.8 work units) at 513 x 513 for M = 20 ... 1000; cycle 3 (33.9) at 257 x 257
for M = 20 ... 500 (the residual test: M = 1000); cycles 3-4 on 65 and 129.
With the fraction 0.25 the errors were the same at most (0.11 of the limits)
but M = 200 on 513 x 513 needed cycle 4 (40.3 work units): the estimate's
d_{k-1}/2 guard was 2.2e-3 for H_min after cycle 3 against a limit of 1.9e-3
(true error 7.9e-5); so 0.5, which the replay shows leaving the estimate a
factor 16 of room.  Not adopted: a sign-aware
estimate (|d_k| where the last two changes alternate), which the replay
showed under-estimating the error 11-fold (65 x 65 elliptic, cycle 3) and
4-fold (513 x 513, M = 100, former relaxation).
Divergence (non-finite values, or ``res`` above 1e3 times its value after
the FMG start), stagnation (``res`` reduced by less than a factor
``stall_factor`` over ``stall_cycles`` cycles) or ``max_cycles`` exceeded
raise :class:`~lubedyn.lubrication.errors.ConvergenceError` naming M, L, the grid,
the cycle, the residual and, for ``stop="error"``, the estimate that missed
its limit.  Work units: one relaxation sweep on the target grid = 1, on a
coarser grid the ratio of node counts.

Kernels are numba (``@njit(cache=True)``): :func:`line_relax` (one sweep),
:func:`reynolds_operator`, :func:`band_solve`, and for the coarsest grid
:func:`dense_relaxations` (film, :func:`coefficients_kernel` and sweep in
one call per block of sweeps between H00 updates, for the Barus, Roelands
and constant viscosities and the Dowson-Higginson and constant densities;
other laws take the numpy path).  The line systems are solved by
:func:`_band_solve_line` (band_solve's operations with fixed trip counts:
about twice as fast per row), and the sweeps on the FFT levels read
column-major copies of their arrays (lines run along x: a third faster
per sweep).  Everything else is numpy.  At 257 x 257 the films (FFT and
dense), the line sweeps, the coefficients and the remaining array arithmetic
(operator, residual, norms, transfers) each take a comparable share of a solve;
the thousands of coarsest-grid sweeps are compiled blocks, since in Python their
call overhead would dominate.  benchmarks/ehl.py (``--only multigrid``) times
whole solves.

References: Brandt, Multigrid techniques: 1984 guide (GMD Studien 85) and
Trottenberg, Oosterlee & Schueller, Multigrid (Academic Press 2001) for the
FMG stopping principle; Venner & Lubrecht 2000 (above; relaxation switch 0.3,
under-relaxation 0.4 / 0.2, H00 factor 0.1 for V-, 0.05 for W-cycles, 0.25 times that
for L > 10 or M > 1000 are their published values); Liu, Wang & Liu,
Wear 243 (2000) 101 (DC-FFT).
"""
from __future__ import annotations

import logging
from dataclasses import dataclass

import numpy as np
import scipy.fft
from numba import njit

from ..elastic import ElasticKernel
from ..errors import ConvergenceError, InputError
from ..laws import lubricant as L

log = logging.getLogger(__name__)

_KL, _KU = 3, 2  # sub- and super-diagonals of a line system
_KX, _KY = 7, 2  # local influence stencil kept for the line systems: |dx| < 7, |dy| < 2
_DENSE_MAX = 600  # grids up to this many nodes deflect by a dense product instead of the FFT


# ---------------------------------------------------------------- numba kernels
@njit(cache=True)
def _row_operator(P, H, rho, eps, i, j, rx2, ry2, rhx, order):
    e0 = eps[i, j]
    xe = 0.5 * (eps[i + 1, j] + e0) * rx2
    xw = 0.5 * (eps[i - 1, j] + e0) * rx2
    xn = 0.5 * (eps[i, j + 1] + e0) * ry2
    xs = 0.5 * (eps[i, j - 1] + e0) * ry2
    q = xe * P[i + 1, j] + xw * P[i - 1, j] + xn * P[i, j + 1] + xs * P[i, j - 1] - (xe + xw + xn + xs) * P[i, j]
    if order == 2 and i >= 2:
        w = rhx * (1.5 * rho[i, j] * H[i, j] - 2.0 * rho[i - 1, j] * H[i - 1, j] + 0.5 * rho[i - 2, j] * H[i - 2, j])
    else:
        w = rhx * (rho[i, j] * H[i, j] - rho[i - 1, j] * H[i - 1, j])
    return q - w, w


@njit(cache=True)
def reynolds_operator(P, H, rho, eps, K, hx, hy, order, out, wedge, diag):
    """Discrete Reynolds operator L(P) (Poiseuille minus wedge) at the interior
    nodes into ``out``, the wedge term d(rho H)/dX into ``wedge`` and the
    diagonal dL_i/dP_i (elastic part through the influence coefficient
    ``K[0, 0]``, ``K`` as in :func:`line_relax`) into ``diag`` (boundary: 0)."""
    nx, ny = P.shape
    rx2, ry2, rhx = 1.0 / (hx * hx), 1.0 / (hy * hy), 1.0 / hx
    out[:, :] = 0.0
    wedge[:, :] = 0.0
    diag[:, :] = 0.0
    for i in range(1, nx - 1):
        for j in range(1, ny - 1):
            out[i, j], wedge[i, j] = _row_operator(P, H, rho, eps, i, j, rx2, ry2, rhx, order)
            e0 = eps[i, j]
            sx = (0.5 * (eps[i + 1, j] + eps[i - 1, j]) + e0) * rx2 + (0.5 * (eps[i, j + 1] + eps[i, j - 1]) + e0) * ry2
            if order == 2 and i >= 2:
                dw = rhx * (1.5 * rho[i, j] * K[0, 0] - 2.0 * rho[i - 1, j] * K[1, 0] + 0.5 * rho[i - 2, j] * K[2, 0])
            else:
                dw = rhx * (rho[i, j] * K[0, 0] - rho[i - 1, j] * K[1, 0])
            diag[i, j] = -sx - dw


@njit(cache=True)
def band_solve(S, y, n, kl, ku):
    """Solve A x = y in place (x returned in ``y``) for a band matrix with
    ``kl`` sub- and ``ku`` super-diagonals, rows stored as windows
    S[r, c - r + kl] = A[r, c] (width 2 kl + ku + 1: room for the fill of
    partial pivoting).  Gaussian elimination with partial pivoting.  Returns
    False if a pivot is zero."""
    for k in range(n):
        best = k
        amax = abs(S[k, kl])
        for r in range(k + 1, min(n, k + kl + 1)):
            v = abs(S[r, k - r + kl])
            if v > amax:
                amax = v
                best = r
        if amax == 0.0:
            return False
        if best != k:
            for c in range(k, min(n, k + kl + ku + 1)):
                wk = c - k + kl
                wb = c - best + kl
                t = S[k, wk]
                S[k, wk] = S[best, wb]
                S[best, wb] = t
            t = y[k]
            y[k] = y[best]
            y[best] = t
        piv = S[k, kl]
        for r in range(k + 1, min(n, k + kl + 1)):
            m = S[r, k - r + kl] / piv
            if m != 0.0:
                for c in range(k + 1, min(n, k + kl + ku + 1)):
                    S[r, c - r + kl] -= m * S[k, c - k + kl]
                S[r, k - r + kl] = 0.0
                y[r] -= m * y[k]
    for k in range(n - 1, -1, -1):
        s = y[k]
        for c in range(k + 1, min(n, k + kl + ku + 1)):
            s -= S[k, c - k + kl] * y[c]
        y[k] = s / S[k, kl]
    return True


@njit(cache=True)
def _band_solve_line(S, y, n):
    """:func:`band_solve` for the line systems (kl = 3, ku = 2, window width 9)
    with the same operations in the same order, so the same result to the bit
    (tested), but with fixed trip counts: ``S`` and ``y`` carry three rows
    below the n of the system, zero in S, so the pivot search and the
    elimination need no ``min(n, ...)`` bounds (a zero sub-diagonal entry
    gives m = 0 and no update; columns >= n of S are zero and only ever feed
    columns >= n), and the loops unroll: about twice as fast per row as
    band_solve without pivoting, somewhat faster with frequent pivoting.
    Returns False if a pivot is zero."""
    for k in range(n):
        best = k
        amax = abs(S[k, 3])
        v = abs(S[k + 1, 2])
        if v > amax:
            amax = v
            best = k + 1
        v = abs(S[k + 2, 1])
        if v > amax:
            amax = v
            best = k + 2
        v = abs(S[k + 3, 0])
        if v > amax:
            amax = v
            best = k + 3
        if amax == 0.0:
            return False
        if best != k:
            d = best - k
            for c in range(k, min(n, k + 6)):
                wk = c - k + 3
                t = S[k, wk]
                S[k, wk] = S[best, wk - d]
                S[best, wk - d] = t
            t = y[k]
            y[k] = y[best]
            y[best] = t
        piv = S[k, 3]
        for dr in range(1, 4):
            r = k + dr
            m = S[r, 3 - dr] / piv
            if m != 0.0:
                for dc in range(1, 6):
                    S[r, dc - dr + 3] -= m * S[k, dc + 3]
                S[r, 3 - dr] = 0.0
                y[r] -= m * y[k]
    for k in range(n - 1, -1, -1):
        s = y[k]
        for dc in range(1, min(6, n - k)):
            s -= S[k, dc + 3] * y[k + dc]
        y[k] = s / S[k, 3]
    return True


@njit(cache=True)
def line_relax(P, H, rho, eps, f, K, hx, hy, order, switch, omega_gs, omega_jac, eps_ratio=0.0, ratio_pressure=0.5):
    """One sweep of the mixed Gauss-Seidel / Jacobi-distributive line
    relaxation (lines along x, the module docstring's scheme) of
    L(P) = f, in place on ``P``.  ``K[d, e]``: dimensionless influence
    coefficient (dH per unit P) at offsets |dx| = d < 7, |dy| = e < 2.
    ``eps_ratio`` > 0: a row with some eps_{+-1/2}/h^2 > ``switch`` and
    P > ``ratio_pressure`` is Gauss-Seidel only if max/min of eps over its
    five nodes is below ``eps_ratio`` (else Jacobi-distributive); 0: no such
    condition.
    Returns the number of Jacobi-distributive rows."""
    nx, ny = P.shape
    n = nx - 2
    kl, ku = 3, 2
    width = 2 * kl + ku + 1
    Pold = P.copy()
    S = np.zeros((n + _KL, width))  # three zero rows below: _band_solve_line's fixed trip counts
    y = np.zeros(n + _KL)
    gsrow = np.zeros(n, dtype=np.bool_)
    dK = np.zeros(6)
    rx2, ry2, rhx = 1.0 / (hx * hx), 1.0 / (hy * hy), 1.0 / hx
    njac = 0
    for j in range(1, ny - 1):
        S[:, :] = 0.0
        for i in range(1, nx - 1):
            r = i - 1
            e0 = eps[i, j]
            xe = 0.5 * (eps[i + 1, j] + e0) * rx2
            xw = 0.5 * (eps[i - 1, j] + e0) * rx2
            xn = 0.5 * (eps[i, j + 1] + e0) * ry2
            xs = 0.5 * (eps[i, j - 1] + e0) * ry2
            sx = xe + xw + xn + xs
            gs = xe > switch or xw > switch or xn > switch or xs > switch
            if gs and eps_ratio > 0.0 and P[i, j] > ratio_pressure:
                # the Gauss-Seidel row freezes eps, which varies by orders of magnitude over a node where the
                # viscosity's exponential meets a steep high pressure (the outlet spike): Jacobi-distributive
                # there (the inlet rows, P < ratio_pressure, stay Gauss-Seidel: measured slower otherwise)
                emax = max(e0, eps[i + 1, j], eps[i - 1, j], eps[i, j + 1], eps[i, j - 1])
                emin = min(e0, eps[i + 1, j], eps[i - 1, j], eps[i, j + 1], eps[i, j - 1])
                gs = emax < eps_ratio * emin
            gsrow[r] = gs
            if gs:
                Lv, _ = _row_operator(P, H, rho, eps, i, j, rx2, ry2, rhx, order)
            else:
                Lv, _ = _row_operator(Pold, H, rho, eps, i, j, rx2, ry2, rhx, order)
                njac += 1
            y[r] = f[i, j] - Lv
            for d in range(6):
                if gs:
                    dK[d] = K[d, 0]
                else:
                    dK[d] = K[d, 0] - 0.25 * (K[abs(d - 1), 0] + K[d + 1, 0] + 2.0 * K[d, 1])
            if order == 2 and i >= 2:
                c0, c1, c2 = 1.5 * rho[i, j], -2.0 * rho[i - 1, j], 0.5 * rho[i - 2, j]
            else:
                c0, c1, c2 = rho[i, j], -rho[i - 1, j], 0.0
            # d(-wedge_i)/dP_{i+c} = -(c0 K|c| + c1 K|c+1| + c2 K|c+2|)/hx
            diag = -rhx * (c0 * dK[0] + c1 * dK[1] + c2 * dK[2])
            diag -= sx if gs else 1.25 * sx
            S[r, kl] = diag
            full = True
            for c in range(-2, 3):
                ii = i + c
                if 0 <= ii < nx and P[ii, j] <= 0.0:
                    full = False
            if full:
                for c in (-3, -2, -1, 1, 2):
                    col = r + c
                    if col < 0 or col >= n:
                        continue
                    a = -rhx * (c0 * dK[abs(c)] + c1 * dK[abs(c + 1)] + c2 * dK[abs(c + 2)])
                    if c == -1:
                        a += xw if gs else xw + 0.25 * sx
                    elif c == 1:
                        a += xe if gs else xe + 0.25 * sx
                    elif c == -2 and not gs:
                        a -= 0.25 * xw
                    elif c == 2 and not gs:
                        a -= 0.25 * xe
                    S[r, c + kl] = a
        if not _band_solve_line(S, y, n):
            y[:] = 0.0
        for i in range(1, nx - 1):
            r = i - 1
            if gsrow[r]:
                v = P[i, j] + omega_gs * y[r]
                P[i, j] = v if v > 0.0 else 0.0
            else:
                p0 = P[i, j]
                v = p0 + omega_jac * y[r]
                v = v if v > 0.0 else 0.0
                P[i, j] = v
                d = v - p0
                if v > 0.0 and P[i - 1, j] > 0.0 and P[i + 1, j] > 0.0 and P[i, j - 1] > 0.0 and P[i, j + 1] > 0.0:
                    if i > 1:
                        P[i - 1, j] = max(P[i - 1, j] - 0.25 * d, 0.0)
                    if i < nx - 2:
                        P[i + 1, j] = max(P[i + 1, j] - 0.25 * d, 0.0)
                    if j > 1:
                        P[i, j - 1] = max(P[i, j - 1] - 0.25 * d, 0.0)
                    if j < ny - 2:
                        P[i, j + 1] = max(P[i, j + 1] - 0.25 * d, 0.0)
    return njac


# ---------------------------------------------------------------- compiled coefficients and coarsest grid
# Viscosity and density laws the kernels below evaluate themselves (codes; parameters in a float array);
# any other law is evaluated by its Python object (MultigridEHL.coefficients, the numpy path).
_VISC_CONSTANT, _VISC_BARUS, _VISC_ROELANDS = 0, 1, 2
_DENS_CONSTANT, _DENS_DOWSON_HIGGINSON = 0, 1


def _law_codes(viscosity, density):
    """``(vcode, vpar, dcode, dpar)`` of the kernels' laws, or None for a law they do not know
    (exact types only: a subclass may change ``__call__``)."""
    t = type(viscosity)
    if t is L.ConstantViscosity:
        v = (_VISC_CONSTANT, np.array([viscosity.eta0, 0.0, 0.0, 0.0]))
    elif t is L.Barus:
        v = (_VISC_BARUS, np.array([viscosity.eta0, viscosity.alpha, 0.0, 0.0]))
    elif t is L.Roelands:
        v = (_VISC_ROELANDS, np.array([viscosity.eta0, viscosity._c, viscosity.p0, viscosity.z]))
    else:
        return None
    t = type(density)
    if t is L.Incompressible:
        d = (_DENS_CONSTANT, np.array([density.rho0, 0.0, 0.0]))
    elif t is L.DowsonHigginson:
        d = (_DENS_DOWSON_HIGGINSON, np.array([density.rho0, density.a, density.b]))
    else:
        return None
    return v[0], v[1], d[0], d[1]


@njit(cache=True, error_model="numpy")
def coefficients_kernel(P, H, ph, lam, vcode, vpar, dcode, dpar, rho, eps):
    """rho/rho0 and eps = rho H+^3/(eta/eta0 lambda) at p = ph max(P, 0) into ``rho``, ``eps``:
    the expressions of the laws' ``__call__`` (lubedyn.lubrication.laws.lubricant; Barus, Roelands,
    constant viscosity; Dowson-Higginson, incompressible) node by node, for the coarsest grid
    (:func:`dense_relaxations`), where numpy's per-call overhead dominates; equal to 7e-15
    (Roelands' pow), 4e-16 otherwise.  Not used on the finer grids: numpy's vectorised exp is
    faster there.
    A diverging iterate overflows exp to inf and gives eps = nan, as the numpy path does."""
    nx, ny = P.shape
    eta0, rho0 = vpar[0], dpar[0]
    for i in range(nx):
        for j in range(ny):
            q = ph * max(P[i, j], 0.0)
            if vcode == 1:
                eta = eta0 * np.exp(vpar[1] * q) / eta0
            elif vcode == 2:
                eta = eta0 * np.exp(vpar[1] * ((1.0 + q / vpar[2]) ** vpar[3] - 1.0)) / eta0
            else:
                eta = eta0 / eta0
            if dcode == 1:
                r = rho0 * (1.0 + dpar[1] * q / (1.0 + dpar[2] * q)) / rho0
            else:
                r = rho0 / rho0
            h = max(H[i, j], 0.0)
            rho[i, j] = r
            eps[i, j] = r * (h * h * h) / (eta * lam)


@njit(cache=True, error_model="numpy")
def dense_relaxations(count, P, H00, rigid, hcorr, dense, f, K, hx, hy, order, switch, omega_gs, omega_jac,
                      ph, lam, vcode, vpar, dcode, dpar, H, rho, eps):
    """``count`` relaxation sweeps of a grid whose deflection is the dense product (the coarsest):
    before each, the film H = H00 + rigid + hcorr + dense P and the coefficients as
    :meth:`MultigridEHL.film` and :func:`coefficients_kernel`, then :func:`line_relax`; one call
    instead of three Python-level calls per sweep (17 x 17: 20 sweeps per visit, 16 visits per
    W-cycle; thousands of sweeps in a 257 x 257 solve)."""
    nx, ny = P.shape
    for _ in range(count):
        u = np.dot(dense, P.reshape(nx * ny))
        for i in range(nx):
            for j in range(ny):
                H[i, j] = (rigid[i, j] + H00) + hcorr[i, j] + u[i * ny + j]
        coefficients_kernel(P, H, ph, lam, vcode, vpar, dcode, dpar, rho, eps)
        line_relax(P, H, rho, eps, f, K, hx, hy, order, switch, omega_gs, omega_jac)


# ---------------------------------------------------------------- elastic deflection
def _deflect(P, fft_shape, spectrum):
    """The DC-FFT product ``irfftn(rfftn(P, s) * spectrum, s)[:nx, :ny]`` with the
    padding rows left out of the row transforms: the real transforms along y run
    on the nx rows of ``P`` only (not on the F0 - nx zero rows of the padded
    array, nor, backwards, on the rows that are cut off), the complex ones along
    x on every column as before.  The same 1-D transforms in the same order as
    scipy's ``rfftn``/``irfftn`` (equal to 1.3e-15 of the largest deflection;
    not bitwise: pocketfft vectorises the n-D transform differently).  About
    twice as fast as ``rfftn``/``irfftn`` at 257 x 257 and 513 x 513, a little
    faster on small grids."""
    nx, ny = P.shape
    F0, F1 = fft_shape
    A = scipy.fft.rfft(P, n=F1, axis=1)
    A = scipy.fft.fft(A, n=F0, axis=0, overwrite_x=True)
    A *= spectrum
    A = scipy.fft.ifft(A, axis=0, overwrite_x=True)[:nx]
    return scipy.fft.irfft(A, n=F1, axis=1)[:, :ny]


# ---------------------------------------------------------------- grid transfers (numpy)
def _full_weighting(A):
    """Full-weighting restriction (1/16 [1 2 1; 2 4 2; 1 2 1]) to the interior coarse nodes."""
    nc = ((A.shape[0] - 1) // 2 + 1, (A.shape[1] - 1) // 2 + 1)
    out = np.zeros(nc)
    c = A[2:-2:2, 2:-2:2]
    e = A[1:-3:2, 2:-2:2] + A[3:-1:2, 2:-2:2] + A[2:-2:2, 1:-3:2] + A[2:-2:2, 3:-1:2]
    d = A[1:-3:2, 1:-3:2] + A[3:-1:2, 1:-3:2] + A[1:-3:2, 3:-1:2] + A[3:-1:2, 3:-1:2]
    out[1:-1, 1:-1] = (4 * c + 2 * e + d) / 16.0
    return out


def _restrict_pressure(P):
    """Full weighting, injection where one of the nine fine nodes is cavitated (P = 0)."""
    out = _full_weighting(P)
    inj = P[::2, ::2]
    sl = [slice(1, -3, 2), slice(2, -2, 2), slice(3, -1, 2)]
    mn = np.full(inj[1:-1, 1:-1].shape, np.inf)
    for a in sl:
        for b in sl:
            mn = np.minimum(mn, P[a, b])
    inner = out[1:-1, 1:-1]
    out[1:-1, 1:-1] = np.where(mn > 0.0, inner, inj[1:-1, 1:-1])
    return out


def _bilinear(dc, shape):
    e = np.zeros(shape)
    e[::2, ::2] = dc
    e[1::2, ::2] = 0.5 * (dc[:-1, :] + dc[1:, :])
    e[::2, 1::2] = 0.5 * (dc[:, :-1] + dc[:, 1:])
    e[1::2, 1::2] = 0.25 * (dc[:-1, :-1] + dc[1:, :-1] + dc[:-1, 1:] + dc[1:, 1:])
    return e


def _cubic_axis(a, axis):
    """Four-point cubic interpolation to the midpoints along ``axis`` (one-sided at the ends)."""
    a = np.moveaxis(a, axis, 0)
    nc = a.shape[0]
    out = np.zeros((2 * nc - 1,) + a.shape[1:])
    out[::2] = a
    if nc >= 4:
        out[3:-3:2] = (-a[:-3] + 9 * a[1:-2] + 9 * a[2:-1] - a[3:]) / 16.0
        out[1] = (5 * a[0] + 15 * a[1] - 5 * a[2] + a[3]) / 16.0
        out[-2] = (5 * a[-1] + 15 * a[-2] - 5 * a[-3] + a[-4]) / 16.0
    else:
        out[1::2] = 0.5 * (a[:-1] + a[1:])
    return np.moveaxis(out, 0, axis)


def _fmg_interpolate(Pc):
    P = _cubic_axis(_cubic_axis(Pc, 1), 0)
    P = np.maximum(P, 0.0)
    P[0, :] = P[-1, :] = P[:, 0] = P[:, -1] = 0.0
    return P


# ---------------------------------------------------------------- options and levels
STOP_RULES = ("error", "residual")


@dataclass(frozen=True)
class MultigridOptions:
    """Parameters of the multilevel solver.

    Relaxation parameters, switch and H00 factors are Venner & Lubrecht's
    (2000); cycle type, ``nu0``, ``nu1`` and ``h00_updates`` were chosen by
    the measurements quoted in the module docstring.

    ``order``: upstream order of the wedge term on the target grid (2 or 1),
    ``coarse_order`` on the coarser grids (FAS keeps the target grid's
    solution either way; 1 was tried against the spike oscillation: no
    gain); ``xi_switch``: Gauss-Seidel where eps/h^2 exceeds it, else
    Jacobi-distributive; ``omega_gs``/``omega_jac``: under-relaxation;
    ``coarsest_cells``: cells along x on the coarsest grid; ``nu0``
    relaxations there per visit with ``h00_updates`` H00 updates in between,
    ``nu1``/``nu2`` pre- and post-relaxations; ``gamma`` 1 (V-cycle) or 2
    (W-cycle); ``fmg_cycles`` cycles on each intermediate FMG grid;
    ``h_fact`` the H00 relaxation factor (None: 0.1 for V-, 0.05 for
    W-cycles, times 0.25 for L > 10 or M > 1000, times pi over the contact's
    dimensionless Hertz stiffness 1.5 W/delta); ``rtol``/``load_rtol``: convergence test;
    ``max_cycles``: cycles on the target grid; stagnation: less than a factor
    ``stall_factor`` of residual reduction over ``stall_cycles`` cycles.

    ``stop``: when the cycles on the target grid end (see "Stopping" in the
    module docstring): ``"error"`` (default) when the estimated algebraic
    error of H_c and H_min is at most ``error_fraction`` (0.5) times the
    discretisation error estimated between the FMG levels (and at most
    ``error_cap``, relative, if set; default None: no cap) and the load error
    at most that of H_c and at most ``load_limit``, or when the residual test
    below is met; ``"residual"`` only when the relative projected residual is
    at most ``rtol`` and the load error at most ``load_rtol`` (the default
    before the error stop).  ``gs_eps_ratio``, ``gs_ratio_spacing``,
    ``gs_ratio_pressure``: on grids of spacing at most ``gs_ratio_spacing``
    (in b_x) a row with P > ``gs_ratio_pressure`` is Gauss-Seidel only where
    eps varies by less than ``gs_eps_ratio`` over its five nodes (None: no
    such condition; module docstring, relaxation).
    """

    order: int = 2
    coarse_order: int = 2
    xi_switch: float = 0.3
    gs_eps_ratio: float | None = 100.0
    gs_ratio_spacing: float = 6.0 / 256
    gs_ratio_pressure: float = 0.5
    omega_gs: float = 0.4
    omega_jac: float = 0.2
    coarsest_cells: int = 16
    nu0: int = 20
    nu1: int = 3
    nu2: int = 1
    gamma: int = 2
    h00_updates: int = 3
    fmg_cycles: int = 2
    h_fact: float | None = None
    rtol: float = 1e-5
    load_rtol: float = 1e-5
    max_cycles: int = 60
    stall_cycles: int = 6
    stall_factor: float = 0.7
    stop: str = "error"
    error_fraction: float = 0.5
    error_cap: float | None = None
    load_limit: float = 1e-4

    def __post_init__(self):
        if self.stop not in STOP_RULES:
            raise InputError(f"multigrid.stop = {self.stop!r} is not allowed; choose one of {', '.join(STOP_RULES)}")
        for key in ("error_fraction", "error_cap", "load_limit"):
            v = getattr(self, key)
            if v is None and key == "error_cap":
                continue
            if not 0.0 < v < 1.0:
                raise InputError(f"multigrid.{key} = {v!r} must be in (0, 1)" + (" or None (no cap)" if key ==
                                                                                  "error_cap" else ""))
        if self.gs_eps_ratio is not None and not self.gs_eps_ratio > 1.0:
            raise InputError(f"multigrid.gs_eps_ratio = {self.gs_eps_ratio!r} must be > 1 or None (no condition)")
        for key in ("gs_ratio_spacing", "gs_ratio_pressure"):
            if not getattr(self, key) >= 0.0:
                raise InputError(f"multigrid.{key} = {getattr(self, key)!r} must be >= 0")
        for key in ("order", "coarse_order"):
            if getattr(self, key) not in (1, 2):
                raise InputError(f"multigrid.{key} = {getattr(self, key)!r} is not allowed; choose 1 or 2 "
                                 "(wedge upstream order)")
        if self.gamma not in (1, 2):
            raise InputError(f"multigrid.gamma = {self.gamma!r} is not allowed; choose 1 (V-cycle) or 2 (W-cycle)")
        for key in ("omega_gs", "omega_jac"):
            v = getattr(self, key)
            if not 0.0 < v <= 1.0:
                raise InputError(f"multigrid.{key} = {v!r} must be in (0, 1]")


def _level_spectrum(Kk, kscale):
    """Padded lengths and rfftn spectrum of the influence coefficients ``Kk``
    (offsets -(n-1) .. n-1 per axis, ElasticKernel._kernel) times ``kscale``
    for the DC-FFT product of :func:`_deflect`.

    The coefficients are even in each offset (a uniform load on a rectangle
    centred on the node; equal to 1.5e-14 relative at 257 x 257, round-off of
    the closed form), so the two offsets +-(n-1), which a circular length of
    2n - 2 folds onto one index, carry the same value and 2n - 2 suffices
    instead of 2n - 1 (the outputs 0 .. n-1 see every offset -(n-1) .. n-1
    once): the pair is averaged.  On the multigrid grids 2n - 2 is a power of
    two (512 for 257 nodes, against 540 = next_fast_len(513)), faster at
    every multigrid grid size.  Axes where 2n - 2 is
    not an FFT-friendly length keep next_fast_len(2n - 1)."""
    K = np.asarray(Kk, dtype=float)
    shape = tuple((q + 1) // 2 for q in K.shape)
    fft_shape = []
    for axis, n in enumerate(shape):
        L = 2 * n - 2
        if n > 2 and scipy.fft.next_fast_len(L, real=True) == L:
            K = np.moveaxis(K, axis, 0)
            folded = K[:-1].copy()
            folded[0] = 0.5 * (K[0] + K[-1])  # offsets -(n-1) and n-1: one index mod 2n - 2
            K = np.moveaxis(folded, 0, axis)
        else:
            L = scipy.fft.next_fast_len(2 * n - 1, real=True)
        fft_shape.append(L)
    padded = np.zeros(fft_shape)
    idx = [np.arange(-(n - 1), -(n - 1) + k) % q for n, k, q in zip(shape, K.shape, fft_shape)]
    padded[np.ix_(*idx)] = K
    return tuple(fft_shape), scipy.fft.rfftn(padded) * kscale


class _Level:
    def __init__(self, X, Y, bx, e_star, kscale, ratio, kernel=None):
        self.X, self.Y = X, Y
        self.shape = (X.size, Y.size)
        self.hx, self.hy = X[1] - X[0], Y[1] - Y[0]
        self.kernel = kernel or ElasticKernel(self.shape, (self.hx * bx, self.hy * bx), e_star)
        self.kscale = kscale
        nx, ny = self.shape
        Kk = self.kernel._kernel
        K = np.zeros((_KX, _KY))
        mx, my = min(_KX, nx), min(_KY, ny)
        K[:mx, :my] = Kk[nx - 1:nx - 1 + mx, ny - 1:ny - 1 + my] * kscale
        self.K = K
        self.fft_shape, self.spectrum = _level_spectrum(Kk, kscale)
        self.dense = None
        if nx * ny <= _DENSE_MAX:
            # small (coarsest) grids: the same influence coefficients as a dense
            # matrix (an FFT call's overhead is most of its cost there)
            ix, iy = np.meshgrid(np.arange(nx), np.arange(ny), indexing="ij")
            ix, iy = ix.ravel(), iy.ravel()
            self.dense = Kk[ix[:, None] - ix[None, :] + nx - 1, iy[:, None] - iy[None, :] + ny - 1] * kscale
        self.rigid = 0.5 * X[:, None] ** 2 + 0.5 * ratio * Y[None, :] ** 2
        self.P = np.zeros(self.shape)
        self.f = np.zeros(self.shape)
        self.hcorr = np.zeros(self.shape)
        self.rg = 0.0
        self.N = nx * ny


class MultigridEHL:
    """FAS multigrid solve of one steady point contact (see the module docstring).

    Parameters: ``problem`` an :class:`lubedyn.lubrication.ehl._Problem`-like object
    of the target grid (Hertz scales ``bx``, ``by``, ``ph``, ``hscale``, node
    axes ``xs``, ``ys`` and the elastic ``kernel``), the contact, and
    :class:`MultigridOptions`.
    """

    def __init__(self, problem, contact, options: MultigridOptions = MultigridOptions()):
        self.pb, self.c, self.o = problem, contact, options
        lub = contact.lubricant
        self.visc, self.dens = lub.viscosity, lub.density
        self.eta0 = float(self.visc(np.zeros(1))[0])
        self.rho0 = float(self.dens(np.zeros(1))[0])
        self._laws = _law_codes(self.visc, self.dens)  # None: the laws' own __call__ (numpy)
        pb = problem
        self.lam = 12 * contact.mean_speed * self.eta0 * contact.radius_x**2 / (pb.ph * pb.bx**3)
        self.target = (contact.load / (pb.ph * pb.bx**2)) if contact.load is not None else None
        kscale = pb.ph / pb.hscale
        ratio = contact.radius_x / contact.radius_y
        X, Y = pb.xs / pb.bx, pb.ys / pb.bx
        levels = [_Level(X, Y, pb.bx, contact.e_star, kscale, ratio, kernel=pb.kernel)]
        while (levels[-1].shape[0] - 1) // 2 >= options.coarsest_cells and all(
                (n - 1) % 2 == 0 and (n - 1) // 2 >= 4 for n in levels[-1].shape):
            X, Y = X[::2], Y[::2]
            levels.append(_Level(X, Y, pb.bx, contact.e_star, kscale, ratio))
        self.levels = levels[::-1]  # coarsest first
        for lv in self.levels:
            lv.order = options.coarse_order
        self.levels[-1].order = options.order
        self.H00 = 0.0
        self.work = 0.0
        mf = contact.moes_M
        hf = 0.1 if options.gamma == 1 else 0.05
        if contact.moes_L > 10 + 1e-9 or mf > 1000 + 1e-9:
            hf *= 0.25
        # Venner's factors are for the circular contact, whose dry Hertz stiffness
        # -dW/dH00 = 1.5 W/delta is pi in these units; scale by the contact's own
        # (measured need: R_y = 4 R_x, stiffness 2.4 times larger, H00 oscillated)
        delta = getattr(problem, "delta_hertz", None)
        if self.target is not None and delta:
            hf *= np.pi / (1.5 * self.target / (delta / pb.hscale))
        self.h_fact = options.h_fact if options.h_fact is not None else hf

    # -- film and coefficients -----------------------------------------
    def film(self, lv):
        H = np.add(lv.rigid, self.H00)
        H += lv.hcorr
        if lv.dense is not None:
            H += (lv.dense @ lv.P.ravel()).reshape(lv.shape)
            return H
        H += _deflect(lv.P, lv.fft_shape, lv.spectrum)
        return H

    def coefficients(self, lv, H):
        p = self.pb.ph * np.maximum(lv.P, 0.0)
        # a diverging iterate overflows the viscosity (inf / inf = nan below): no warning here, the
        # cycle's non-finite residual stops the solve with "diverged"
        with np.errstate(over="ignore", invalid="ignore"):
            eta = self.visc(p) / self.eta0
            rho = self.dens(p) / self.rho0
            eps = rho * np.maximum(H, 0.0) ** 3 / (eta * self.lam)
        return rho, eps

    def residual(self, lv, H=None):
        """r = f - L(P) (interior), the wedge term and the film."""
        H = self.film(lv) if H is None else H
        rho, eps = self.coefficients(lv, H)
        Lv = np.zeros(lv.shape)
        wedge = np.zeros(lv.shape)
        diag = np.zeros(lv.shape)
        reynolds_operator(lv.P, H, rho, eps, lv.K, lv.hx, lv.hy, lv.order, Lv, wedge, diag)
        r = lv.f - Lv
        r[0, :] = r[-1, :] = r[:, 0] = r[:, -1] = 0.0
        self._diag = diag
        return r, wedge, H, rho, eps

    def relax_many(self, k, count):
        """``count`` sweeps of :meth:`relax` on level ``k``; on a dense-product level with
        laws the kernels know, in one compiled call (:func:`dense_relaxations`)."""
        lv = self.levels[k]
        if lv.dense is None or self._laws is None:
            for _ in range(count):
                self.relax(k)
            return
        if count <= 0:
            return
        o = self.o
        H, rho, eps = np.empty(lv.shape), np.empty(lv.shape), np.empty(lv.shape)
        dense_relaxations(count, lv.P, float(self.H00), lv.rigid, lv.hcorr, lv.dense, lv.f, lv.K, lv.hx, lv.hy,
                          lv.order, o.xi_switch, o.omega_gs, o.omega_jac, self.pb.ph, self.lam, *self._laws,
                          H, rho, eps)
        for _ in range(count):
            self.work += lv.N / self.levels[-1].N

    def relax(self, k):
        lv = self.levels[k]
        H = self.film(lv)
        rho, eps = self.coefficients(lv, H)
        o = self.o
        ratio = o.gs_eps_ratio if (o.gs_eps_ratio is not None and lv.hx <= o.gs_ratio_spacing * (1 + 1e-9)) else 0.0
        if lv.dense is None:
            # the sweep reads the arrays along x (lines i = 1 .. nx - 2 at fixed j): column-major copies make
            # those reads contiguous; the same arithmetic (equal to the bit), a third faster per sweep, the
            # five copies a small fraction of it
            P = np.asfortranarray(lv.P)
            line_relax(P, np.asfortranarray(H), np.asfortranarray(rho), np.asfortranarray(eps),
                       np.asfortranarray(lv.f), lv.K, lv.hx, lv.hy, lv.order, o.xi_switch, o.omega_gs, o.omega_jac,
                       ratio, o.gs_ratio_pressure)
            lv.P[...] = P
        else:
            line_relax(lv.P, H, rho, eps, lv.f, lv.K, lv.hx, lv.hy, lv.order, o.xi_switch, o.omega_gs, o.omega_jac,
                       ratio, o.gs_ratio_pressure)
        self.work += lv.N / self.levels[-1].N

    def load(self, lv):
        return lv.hx * lv.hy * float(np.sum(lv.P))

    def relax_h00(self, k):
        if self.target is None:
            return
        lv = self.levels[k]
        g = self.load(lv) + lv.rg
        self.H00 += self.h_fact * g

    # -- cycles -----------------------------------------------------------
    def cycle(self, k):
        o = self.o
        if k == 0:
            m = max(1, o.h00_updates)
            for s in range(m):
                self.relax_many(0, o.nu0 // (m + 1))
                self.relax_h00(0)
            self.relax_many(0, o.nu0 - m * (o.nu0 // (m + 1)))
            return
        fine, coarse = self.levels[k], self.levels[k - 1]
        for _ in range(o.nu1):
            self.relax(k)
        r, _, Hf, _, _ = self.residual(fine)
        r[fine.P <= 0.0] = 0.0
        coarse.P = _restrict_pressure(fine.P)
        P_old = coarse.P.copy()
        coarse.hcorr = np.zeros(coarse.shape)
        coarse.hcorr = Hf[::2, ::2] - self.film(coarse)
        coarse.f = np.zeros(coarse.shape)
        Lc = -self.residual(coarse)[0]  # f = 0: -r = L(P_c)
        coarse.f = Lc + _full_weighting(r)
        coarse.f[0, :] = coarse.f[-1, :] = coarse.f[:, 0] = coarse.f[:, -1] = 0.0
        coarse.rg = fine.rg + self.load(fine) - self.load(coarse)
        for _ in range(o.gamma):
            self.cycle(k - 1)
        e = _bilinear(coarse.P - P_old, fine.shape)
        fine.P = np.maximum(np.where(fine.P > 0.0, fine.P + e, fine.P), 0.0)
        for _ in range(o.nu2):
            self.relax(k)

    def norms(self, k):
        """Relative projected residual, relative load error and the film.

        The residual is the complementarity ("natural") residual of the
        pointwise Newton step: d_i = max(P_i + r_i/a_ii, 0) - P_i (a_ii =
        dL_i/dP_i < 0), summed over the interior and divided by sum P.  It
        vanishes exactly at a solution of P >= 0, r >= 0 where P = 0, r = 0
        where P > 0, and is not dominated by nodes at the free boundary whose
        tiny pressures flip between 0 and 1e-7 (as sum |r| over P > 0 is)."""
        lv = self.levels[k]
        r, wedge, H, _, _ = self.residual(lv)
        a = self._diag[1:-1, 1:-1]
        Pi = lv.P[1:-1, 1:-1]
        # a diverging iterate overflows these sums: no warning here, the non-finite residual stops the solve
        # with "diverged" (as in coefficients)
        with np.errstate(over="ignore", invalid="ignore"):
            d = np.maximum(Pi + r[1:-1, 1:-1] / np.where(a < 0, a, -1.0), 0.0) - Pi
            res = float(np.sum(np.abs(d)) / max(np.sum(Pi), 1e-300))
        load_err = ((self.load(lv) - self.target) / self.target) if self.target is not None else 0.0
        return res, load_err, H

    def _hint(self, lv) -> str:
        """What to try, from the contact's load parameter (measured, L = 10 and 20)."""
        c = self.c
        if c.radius_y is not None and max(c.radius_y / c.radius_x, c.radius_x / c.radius_y) > 4.0:
            return (f"M = {c.moes_M:.4g} on an elongated contact (R_y/R_x = {c.radius_y / c.radius_x:.3g}): the "
                    "multigrid's line relaxation and transfers assume square cells, and finer grids do not help "
                    "(measured: paper B's ball, k = 11, M = 1001, stagnates on 129 x 33 and 257 x 1425 and diverges "
                    "on 513 x 2849); use [solver] method = 'auto' (the Newton methods solve it on 33 x 17 ... "
                    "129 x 33)")
        if self.c.moes_M >= 1000:
            nx = lv.shape[0]
            need = 513 if self.c.moes_M > 2000 else 257
            grid = f"[grid] nx >= {max(need, 2 * (nx - 1) + 1)}" if nx < 513 else "a finer [grid] nx"
            return (f"M = {self.c.moes_M:.4g} is a very heavily loaded (or slow) contact, which needs a finer grid "
                    "(measured: M = 2000, L = 10 converges from 257 x 257, M = 3000 stagnates on 257 x 257 and "
                    f"converges on 513 x 513): use {grid} (EHLGrid.nx)")
        return (f"M = {self.c.moes_M:.4g} is not a heavy load; light loads at high L stop on fine grids "
                "(measured: M = 10-50, L = 20 stagnate or diverge on 257 x 257 and 513 x 513, M = 10-20 "
                "converge on 129 x 129): try a coarser grid, or solver.method = 'auto'")

    def _fail(self, what, k, cycle, res, detail=""):
        lv = self.levels[k]
        err = ConvergenceError(
            f"EHL multigrid {what} at M = {self.c.moes_M:.4g}, L = {self.c.moes_L:.4g} on {lv.shape[0]} x "
            f"{lv.shape[1]} nodes, cycle {cycle}: relative residual {res:.2e} (tolerance {self.o.rtol:.0e}){detail}; "
            f"{self._hint(lv)}; from Python the cycle and tolerance settings are EHLOptions.multigrid "
            "(MultigridOptions)")
        reason = "iteration limit" if what.startswith("did not converge") else what  # diverged, stagnated
        err.stop = dict(reason=reason, detail=str(err))
        return err

    def _films(self, lv):
        """(H at the node nearest X = Y = 0, min H) of level ``lv``'s pressure."""
        H = self.film(lv)
        ic = (int(np.argmin(np.abs(lv.X))), int(np.argmin(np.abs(lv.Y))))
        return float(H[ic]), float(np.min(H))

    def _error_test(self, history, coarse, coarse2=None):
        """The error-based stop after the last cycle in ``history``: a dict of
        the relative algebraic-error estimates of H_c, H_min and the load, the
        relative discretisation-error estimates of H_c and H_min, the limits
        ``error_fraction`` x discretisation error (at most ``error_cap`` if set)
        and ``met`` (see "Stopping" in the module docstring).  ``coarse`` and
        ``coarse2``: H_c, H_min of the FMG solutions two and four times coarser
        (None where there is none)."""
        o = self.o
        h = history
        out = dict(met=False)
        p = 2.0**o.order - 1.0
        # a coarse grid whose film has collapsed (H_min <= 0) is no solution: no discretisation-error estimate
        if coarse is not None and min(coarse["H_centre"], coarse["H_min"]) <= 0.0:
            coarse = None
        if coarse2 is not None and (coarse is None or min(coarse2["H_centre"], coarse2["H_min"]) <= 0.0):
            coarse2 = None
        worst = None
        for key, name in (("H_centre", "H_c"), ("H_min", "H_min")):
            q = h[-1][key]
            d1 = abs(q - h[-2][key])
            d0 = abs(h[-2][key] - h[-3][key]) if len(h) >= 3 else 0.0
            r = min(d1 / d0, 0.9) if d0 > 0.0 else 0.5
            # remaining error of a geometric sequence of changes, d1 r/(1 - r), but at least the last
            # change and half the one before (non-monotone histories: a small d1 can be a sign change)
            e_alg = max(d1, 0.5 * d0) * max(1.0, r / (1.0 - r)) / abs(q)
            e_disc = None
            if coarse is not None:
                e_disc = abs(q - coarse[key]) / p / abs(q)
                if coarse2 is not None:  # the coarser pair's difference, scaled by 2^order: a cancellation
                    e_disc = max(e_disc, abs(coarse[key] - coarse2[key]) / (p + 1.0) / p / abs(q))
            if e_disc is None:
                limit = o.error_cap if o.error_cap is not None else 0.0
            else:
                limit = o.error_fraction * e_disc
                if o.error_cap is not None:
                    limit = min(limit, o.error_cap)
            out[name] = dict(algebraic_error=e_alg, discretisation_error=e_disc, limit=limit)
            ratio = e_alg / limit if limit > 0.0 else np.inf  # limit 0: no estimate, or coarse and fine H equal
            if worst is None or ratio > worst[0]:
                worst = (ratio, name)
            if name == "H_c":
                # the load is imposed, not discretised: at most H_c's limit and at most load_limit
                load_limit = min(limit, o.load_limit)
        e_load = abs(h[-1]["load_error"] or 0.0)
        out["load"] = dict(algebraic_error=e_load, limit=load_limit)
        ratio = e_load / load_limit if load_limit > 0.0 else np.inf
        if ratio > worst[0]:
            worst = (ratio, "load")
        out["worst"] = worst[1]
        out["met"] = len(h) >= 3 and worst[0] <= 1.0
        return out

    @staticmethod
    def _describe(test):
        w = test["worst"]
        e = test[w if w != "load" else "H_c"]
        if e.get("discretisation_error") is None:
            how = "; no discretisation-error estimate: no coarser FMG grid, or its film collapsed"
        else:
            how = f" = fraction x discretisation error {e['discretisation_error']:.1e}, or the cap"
        return f"algebraic error of {w} {test[w]['algebraic_error']:.1e} (limit {test[w]['limit']:.1e}{how})"

    def solve(self, H00_start):
        """FMG start, then cycles on the target grid; returns ``(P, H00, history)``
        (P = p/p_H on the target grid; H00 in units of b_x^2/R_x).  The last
        history entry's ``stop`` names the stop rule that ended the cycles
        (``"error"`` or ``"residual"``) and ``stop_detail`` its figures."""
        o = self.o
        self.H00 = float(H00_start)
        nlev = len(self.levels)
        c0 = self.levels[0]
        if self.target is not None:
            for lv in self.levels:
                lv.rg = -self.target
        ry = self.pb.by / self.pb.bx
        r2 = c0.X[:, None] ** 2 + (c0.Y[None, :] / ry) ** 2
        c0.P = np.sqrt(np.clip(1.0 - r2, 0.0, None))
        c0.P[0, :] = c0.P[-1, :] = c0.P[:, 0] = c0.P[:, -1] = 0.0
        self.cycle(0)
        # H_c, H_min of the FMG solutions one and two levels below the target (the discretisation-error
        # estimate and its guard against a cancellation), recorded when each is final; an intermediate
        # grid is a solution only after its FMG cycles, the coarsest always
        fmg_films = {}
        for k in range(1, nlev):
            if k - 1 >= nlev - 3 and (o.fmg_cycles > 0 or nlev == 2):
                fmg_films[k - 1] = dict(zip(("H_centre", "H_min"), self._films(self.levels[k - 1])))
            lv = self.levels[k]
            lv.P = _fmg_interpolate(self.levels[k - 1].P)
            lv.f = np.zeros(lv.shape)
            lv.hcorr = np.zeros(lv.shape)
            lv.rg = -self.target if self.target is not None else 0.0
            if k < nlev - 1:
                for _ in range(o.fmg_cycles):
                    self.cycle(k)
        coarse, coarse2 = fmg_films.get(nlev - 2), fmg_films.get(nlev - 3)
        k = nlev - 1
        top = self.levels[k]
        self._ic = (int(np.argmin(np.abs(top.X))), int(np.argmin(np.abs(top.Y))))
        history = []
        res0, load0, H = self.norms(k)
        history.append(dict(cycle=0, residual=res0, load_error=load0, work=self.work, H00=self.H00,
                            H_centre=float(H[self._ic]), H_min=float(np.min(H)), coarse=coarse, coarse2=coarse2))
        test = None
        for cyc in range(1, o.max_cycles + 1):
            self.cycle(k)
            res, load_err, H = self.norms(k)
            history.append(dict(cycle=cyc, residual=res, load_error=load_err, work=self.work, H00=self.H00,
                                H_centre=float(H[self._ic]), H_min=float(np.min(H))))
            test = self._error_test(history, coarse, coarse2)
            history[-1].update(error_Hc=test["H_c"]["algebraic_error"], error_Hmin=test["H_min"]["algebraic_error"])
            log.debug("EHL multigrid cycle %d: res %.3e, load err %.2e, H00 %.7f, H_c %.7f, H_min %.7f, work %.1f, "
                      "%s", cyc, res, load_err, self.H00, history[-1]["H_centre"], history[-1]["H_min"], self.work,
                      self._describe(test))
            detail = f"; error-based stop not met: {self._describe(test)}" if o.stop == "error" else ""
            if not (np.isfinite(res) and np.isfinite(self.H00)) or res > 1e3 * max(res0, 1e-300):
                raise self._fail("diverged", k, cyc, res, detail)
            if o.stop == "error" and test["met"]:
                history[-1].update(stop="error", stop_detail=(
                    f"algebraic error estimates (relative) H_c {test['H_c']['algebraic_error']:.1e}, H_min "
                    f"{test['H_min']['algebraic_error']:.1e}, load {test['load']['algebraic_error']:.1e} within "
                    f"{o.error_fraction:g} x discretisation error"
                    + (f" (at most {o.error_cap:.0e})" if o.error_cap is not None else "")
                    + f", load at most {o.load_limit:.0e}; worst: "
                    + self._describe(test)))
                break
            if res <= o.rtol and abs(load_err) <= o.load_rtol:
                history[-1].update(stop="residual", stop_detail=(
                    f"relative projected residual {res:.1e} <= rtol {o.rtol:.0e} and load error {abs(load_err):.1e} "
                    f"<= {o.load_rtol:.0e}" + (f"; error-based stop not met: {self._describe(test)}"
                                               if o.stop == "error" else "")))
                break
            if cyc > o.stall_cycles and res > o.stall_factor * history[-1 - o.stall_cycles]["residual"]:
                raise self._fail("stagnated", k, cyc, res, detail)
        else:
            raise self._fail(f"did not converge in {o.max_cycles} cycles", k, o.max_cycles, history[-1]["residual"],
                             f"; error-based stop not met: {self._describe(test)}" if o.stop == "error" and test
                             else "")
        return self.levels[k].P.copy(), self.H00, history
