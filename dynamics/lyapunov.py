"""Lyapunov exponents: full spectrum by Benettin's method, largest exponent from a time series.

Spectrum of a flow (:func:`lyapunov_spectrum`)
-----------------------------------------------
State and ``k`` tangent vectors are integrated together, dy/dt = f(t, y),
dV/dt = J(t, y) V (variational equations), by classical RK4 with a fixed step
``dt`` (each RK4 stage evaluates J at the stage state, so the pair is the RK4
solution of the augmented system).  Every ``t_orth`` the tangent vectors are
re-orthonormalised by a QR factorisation (Gram-Schmidt), V = Q R, V <- Q, and
after the transient the logarithms of |R_ii| are accumulated:
lambda_i = sum log|R_ii| / (time accumulated) [1/s] (Benettin, Galgani,
Giorgilli & Strelcyn, Meccanica 15, 1980; Parker & Chua, *Practical numerical
algorithms for chaotic systems*, ch. 3).  J v comes from a user ``jvp`` (an
@njit ``jvp(t, y, v, args, out)`` writing J(t, y) v) or, when none is given,
from the forward difference (f(y + eps v) - f(y)) / eps with eps = sqrt(2.2e-16)
(1 + |y|) / |v| (one extra rhs call per tangent vector and stage).  The sum
of all n exponents equals the time mean of trace J, exactly for Lorenz:
-(sigma + 1 + beta).  :class:`BenettinRun` is the same method as an object that is advanced in pieces,
watched after every interval (``observe``) and saved and resumed bit for bit; per-direction exponents
from its first tangent vector are :mod:`lubedyn.dynamics.tangent_directions`'.

Spectrum of a map (:func:`lyapunov_spectrum_map`)
-------------------------------------------------
Same, with x_{n+1} = g(x_n) and V <- Dg(x_n) V at every iteration; exponents
per iteration.  Henon (a = 1.4, b = 0.3): 0.4192, -1.6232 (sum ln b).

Largest exponent from a scalar series (:func:`largest_lyapunov_rosenstein`)
----------------------------------------------------------------------------
Rosenstein, Collins & De Luca, Physica D 65 (1993) 117: delay embedding
X_i = (x_i, x_{i+tau}, ..., x_{i+(m-1)tau}); for every X_i its nearest
neighbour X_j with |i - j| > Theiler window; the mean over i of
ln |X_{i+k} - X_{j+k}| against k dt rises with slope lambda_1 until it
saturates at the attractor size; the slope of a straight-line fit over the
linear part is lambda_1 [1/s].

Largest exponent by Wolf et al. (:func:`largest_lyapunov_wolf`)
---------------------------------------------------------------
Wolf, Swift, Swinney & Vastano, Physica D 16 (1985) 285, fixed-evolution-time
algorithm: follow one nearest-neighbour pair of delay vectors for ``evolve``
samples, add log2 of the growth of its separation, keep the evolved
neighbour while the separation stays between ``scale_min`` and ``scale_max``,
else replace it by a point near the fiducial trajectory whose separation
points the same way (angle limit 0.3 rad); lambda_1 = sum log2 / elapsed time
in bits/s (Wolf et al.'s unit), ln 2 times that in 1/s.

Paper B (Zhang et al., Symmetry 2024, 16, 741, section 3.3, Table 3) reports a
"maximum Lyapunov exponent" per direction (X, Y, Z) of a ball, without units,
computed by "the orthogonalization method", i.e. Gram-Schmidt
re-orthonormalisation of tangent vectors, citing Wolf et al., with
lambda_i = (1/(s tau)) log2 p_i (its eqs. 24-27: log base 2, so bits per unit
time if its tau is in seconds).  It does not say how a tangent-space method
gives an exponent per coordinate.  This module offers both readings: the
whole system's spectrum by Gram-Schmidt (:func:`lyapunov_spectrum`, in 1/s)
and per-coordinate exponents from each coordinate's time series by Wolf et
al.'s time-series algorithm (bits/s, as Wolf et al. and paper B's log2) and
by Rosenstein's (1/s).  Neither per-coordinate estimate is known to be what
Table 3 holds.

Wolf et al.'s Table 1 values (bits/s; Henon bits/iteration), used as test
references: Henon (a = 1.4, b = 0.3) 0.603; Lorenz (sigma = 16, R = 45.92,
b = 4.0) 2.16; Rossler (a = 0.15, b = 0.20, c = 10.0) 0.13.  Only the paper's
abstract was retrievable here, so these numbers are as commonly quoted from
its Table 1; :func:`lyapunov_spectrum` on the equations confirms them
independently (Henon 0.4192 / ln 2 = 0.6048; Lorenz 2.173, -32.47 bits/s at
T = 300 s; Rossler 0.1294, -14.14 bits/s at T = 5000 s).

Neighbours come from a k-d tree (``scipy.spatial.cKDTree``), Rosenstein's
divergence average from a numba kernel: 40,000 samples take ~5 s.  Wolf's
walk is one compiled kernel (:func:`_wolf_walk`): its sequential replacement
search cannot be batched into tree queries, and a ball query of a k-d tree
per evolution step from Python cost 30-100 us of call overhead; the compiled
search runs over the slab |X_i,0 - p_0| <= r of the points sorted by their
first coordinate.  Measured against the former tree-and-Python walk
(benchmarks/wolf_walk.py, same process, interleaved): 0.11-0.38 of its CPU
time (20,000 Henon samples: 0.63 against 2.4 s on a loaded 2-core VM), equal
replacements and per-step logs within 9e-16 with the same tie-break.

Measured (full length; smoke-length versions are in tests/test_lyapunov.py)
---------------------------------------------------------------------------
Lorenz, T = 1e4 s after a 10 s transient, t_orth = 0.05 s: dt = 0.005 s ->
(0.90576, 6.6e-5, -14.57248), sum -13.666660 (exact -13.666667); the same with
the forward-difference J: 0.90576, sum -13.666660; dt = 0.01 s -> 0.90628.
Reference 0.9056, 0, -14.5723.  Henon, 1e7 iterations: (0.41915, -1.62313),
sum = ln 0.3 to 1e-13; reference 0.4192, -1.6232.  Rosenstein on 40,000
Lorenz samples (dt 0.01 s, m = 5, tau = 0.1 s, fit 1.0-2.5 s): x 0.869, y
0.859, z 0.805 (-4, -5, -11 %); the default 30-70 % fit window gives 0.834 /
0.822 / 0.771 (it reaches into the bend towards saturation): the method is
biased low by 5-10 % here.  Henon x, 20,000 samples, m = 2: 0.4135.

Wolf et al.'s algorithm (bits/s; references 0.603 / 2.16 / 0.13): Henon x,
m = 2, evolve 1: 0.590-0.622 over 3 initial conditions and 2,000-20,000
samples.  Rossler x (dt 0.1 s, 10,000-20,000 samples, m = 3-4, tau 1-1.5 s,
evolve 1-3 s, scale_max 0.05-0.1 of the range): 0.116-0.148.  Lorenz x (dt
0.01 s, m = 3, tau 0.1 s, evolve 0.15 s, default scales), 6 initial
conditions: 10,000 samples 2.00 +- 0.13 (1.86-2.21), 40,000 samples 1.93 +-
0.09; but over evolve 0.1-0.2 s, m = 3-5 and scale_max 0.05-0.15 of the range
the means move between 1.64 and 2.66, further than their batch-means
uncertainties (0.05-0.18): the time-series estimate depends on its settings
by +-25 % on Lorenz, which the uncertainty does not include.

Guards of a time-series exponent (:func:`assess_largest_lyapunov`)
------------------------------------------------------------------
Wolf's and Rosenstein's estimators give a number for any series, and their own verdicts
(``WolfResult.verdict`` / ``.resolved``, ``RosensteinResult.verdict``) judge it by the spread along one record:
white noise gets 961 +- 8 bits/s and AR(1) noise (phi 0.95) 45.8 +- 2.0 bits/s, "positive" and resolved.
:func:`assess_largest_lyapunov` adds three guards and calls an estimate resolved only when all pass:

1. noise: 19 IAAFT surrogates (Schreiber & Schmitz 1996; or phase-randomised, Theiler et al. 1992;
   :mod:`lubedyn.dynamics.surrogates`, seeded) get the same estimate; the series' must lie outside all
   of theirs and 3 of their standard deviations from their mean;
2. settings: the minimum embedding dimension by false nearest neighbours (Kennel, Brown & Abarbanel
   1992, :func:`false_nearest_neighbours`) must not exceed dim, and the estimates over dim + 1 (dim - 1
   where that is still at least the minimum), delay and evolution time x 2/3 and 3/2 must all lie within
   35 % of their median;
3. convergence: 4 disjoint windows (or independent members) give the uncertainty std / sqrt(K), at most
   25 % of a positive estimate.

Measured with Wolf's method, default settings (delay = evolve = the first minimum of the mutual
information, dim = the false-neighbour minimum), three initial conditions or seeds each
(``tests/test_lyapunov_guards.py``):

- Henon x, 2,000 iterations (dim 2, delay 1): 0.416, 0.400, 0.404 per iteration (reference 0.4192),
  surrogates 1.35-1.37 (z -46 to -67), settings spread 0.03-0.07: "positive", resolved.
- Lorenz x, 5,000 samples at 0.01: 1.070, 1.025, 0.721 1/s (+18, +13, -20 % of 0.906), surrogates
  3.7-4.6 1/s (z -14 to -22), spread 0.04-0.23, window standard error 0.10-0.16: "positive", resolved.
  At 10,000 samples 0.838, 0.963, 0.765 (-8, +6, -16 %).
- One coordinate of Lorenz-96 (10 sites, F = 8; lambda_1 = 1.15 1/s by Benettin), 5,000 samples at
  0.05: 1.81, 1.10, 1.74 1/s; the settings move it over 0.6-3.7 1/s (spread 0.62-0.98) and no dimension
  up to 10 unfolds it; its surrogates give the same in 2 of 3 (z -1.4, 0.4; the third z -3.2): "not
  distinguishable from its surrogates" twice, "depends on the embedding settings" once.
- sin t + 0.7 sin(sqrt 2 t) (lambda = 0): |estimate| <= 0.0012 1/s (window uncertainty 0.004-0.007),
  surrogates 0.077-0.106 1/s (z -5.0 to -7.3), the settings grid -0.001 to 0.004 1/s: "not positive",
  resolved, 3 of 3.  An estimate that is not positive is judged against its resolution 2 x
  uncertainty, not its own size (relative to 0.0002 the grid's scatter was 700-6,000 %): it is
  insensitive to the settings when no grid estimate exceeds that resolution (none would be
  "positive"), and converged when the windows exist and the running estimate moved at most max(20 % of
  it, 2 u), as :func:`verdict` asks.  A pure sine: its surrogates are sines, "not distinguishable".
- White noise, 2,000 samples: 149-709 1/s depending on the delay chosen, z -0.9 to 0.9; AR(1), phi
  0.95, 4,000-5,000 samples: 21-34 1/s, z -0.8 to 2.0: "not distinguishable from its surrogates
  (linear noise)"; no false-neighbour dimension either.
- Lorenz x plus a sine 5 times its range (period 3.7): the record alone at Lorenz' settings "positive",
  resolved, 0.82 1/s; guarded 0.086 and 0.114 1/s, "depends on the embedding settings" (with a sine 1
  times the range: "not distinguishable").

Rosenstein's slope, same guards (``method="rosenstein"``): Lorenz x, 5,000 samples, m = 5, delay 0.1,
fit 1.0-2.5: 0.955, 0.803, 0.672 1/s (+5, -11, -26 %), z 14-32, resolved; the -26 % is 4.6 window
uncertainties off, so the window spread does not bound the method's bias on short records.  AR(1)
(4,000 samples): 233 1/s against 231 +- 6, "not distinguishable"; with another seed the estimator
refuses the record (no divergence rise), as it does white noise of 2,000 samples: its own error.

Limits of the guards: an estimate that passes them is consistent with deterministic low-dimensional
dynamics and stable under the settings, not proven right (the Lorenz estimates above scatter by +-20 %
around the value at 5,000 samples); one coordinate of a 10-dimensional flow cannot be told from linear
noise with 5,000 samples.  The settings rule (35 % of the grid's median) was set after measuring six
Lorenz records (5,000 and 10,000 samples): measured about the central estimate instead of the median,
2 of 6 failed it (38 and 40 %), and with delay and evolution time x 1/2 and 2 (about the central
estimate) 5 of 6 (spread 0.20-0.80).  Cost: 1 + surrogates + 4-6 + windows estimates (30 for Wolf:
2-12 s on these records; Rosenstein 20-45 s).

Non-smooth forces: the variational equations need a continuous Jacobian
along the orbit.  A Hertz force k delta^1.5 has dF/d delta = 1.5 k delta^0.5,
continuous at contact onset, so it is fine; a force with a jump at contact
(e.g. a linear spring-dashpot c d(delta)/dt switched on at delta = 0) needs
saltation matrices, which are not implemented: smooth such laws (or compare
with the Rosenstein estimate) before trusting the spectrum.  The cage-less bearing's
laws are continuous in force; measured there, the tangent vector follows the
secant of two trajectories across contact onsets to first order in the secant's
step, except after a plastic collision (the frozen memory):
:mod:`lubedyn.dynamics.tangent_directions`, "Smoothed contact laws need no saltation matrices".

Units: exponents in 1/s (flows) or per iteration (maps);
:func:`per_shaft_revolution` converts 1/s to 1/rev.
"""
from __future__ import annotations

import logging
import math
from dataclasses import dataclass

import numpy as np
from numba import njit
from numba import types as _nt

from .errors import DynamicsInputError
from .integrators import chunk_bounds, put, put2, rhs_signature, stability_limit
from .specialise import register_kernel, specialise
from .errors import IntegrationError

logger = logging.getLogger(__name__)

FD_EPS = math.sqrt(2.2e-16)


@njit(cache=True)
def no_jvp(t, y, v, args, out):
    """Placeholder jvp: the kernel uses a forward difference of the rhs instead."""
    out[:] = np.nan


def _benettin_impl(rhs, jvp, y, V, keep, scale, args, t0, dt, steps_per_orth, q_begin, q_end, n_transient, use_fd,
                   log_sum, accumulated, running):
    """Orthonormalisation intervals ``q_begin`` .. ``q_end - 1`` of Benettin's method: ``y`` (the scaled
    state z = y / scale; rhs and jvp see z * scale) and the tangent rows ``V`` advance in place, ``log_sum``,
    ``accumulated[0]`` and the rows of ``running`` fill in.  Every quantity carried from one interval to the
    next lives in these arrays and the time is computed from the interval's index, so a run made of several
    calls is bit-identical to one call over all intervals (:func:`lyapunov_spectrum`'s ``n_chunks``).
    Returns ``(t reached, status)``: 0, or 3 for a non-finite state or tangent vector."""
    n = y.shape[0]
    k = V.shape[0]
    ys = np.empty(n)
    Vs = np.empty((k, n))
    ky = np.empty((4, n))
    kV = np.empty((4, k, n))
    f0 = np.empty(n)
    ytmp = np.empty(n)
    ftmp = np.empty(n)
    yr = np.empty(n)  # a state in rhs' units
    vr = np.empty(n)
    t = t0 + (q_begin * steps_per_orth) * dt if q_begin > 0 else t0
    c = (0.0, 0.5, 0.5, 1.0)
    w = (1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0)
    status = 0
    for q in range(q_begin, q_end):
        for s in range(steps_per_orth):
            for stage in range(4):
                if stage == 0:
                    put(ys, 0, y)
                    put2(Vs, V)
                else:
                    a = c[stage] * dt
                    for j in range(n):
                        ys[j] = y[j] + a * ky[stage - 1, j]
                    for i in range(k):
                        for j in range(n):
                            Vs[i, j] = V[i, j] + a * kV[stage - 1, i, j]
                ts = t + c[stage] * dt
                for j in range(n):
                    yr[j] = ys[j] * scale[j]
                rhs(ts, yr, args, f0)
                for j in range(n):
                    f0[j] /= scale[j]
                put(ky[stage], 0, f0)
                for i in range(k):
                    if use_fd:
                        vn = 0.0
                        yn = 0.0
                        for j in range(n):
                            vn += Vs[i, j] * Vs[i, j]
                            yn += ys[j] * ys[j]
                        vn = math.sqrt(vn)
                        if vn == 0.0:
                            kV[stage, i, :] = 0.0
                            continue
                        eps = FD_EPS * (1.0 + math.sqrt(yn)) / vn
                        for j in range(n):
                            ytmp[j] = ys[j] + eps * Vs[i, j]
                        for j in range(n):
                            yr[j] = ytmp[j] * scale[j]
                        rhs(ts, yr, args, ftmp)
                        for j in range(n):
                            ftmp[j] /= scale[j]
                        for j in range(n):
                            kV[stage, i, j] = keep[j] * (ftmp[j] - f0[j]) / eps
                    else:
                        for j in range(n):
                            yr[j] = ys[j] * scale[j]
                            vr[j] = Vs[i, j] * scale[j]
                        jvp(ts, yr, vr, args, ftmp)
                        for j in range(n):
                            kV[stage, i, j] = keep[j] * ftmp[j] / scale[j]
            for j in range(n):
                y[j] += dt * (w[0] * ky[0, j] + w[1] * ky[1, j] + w[2] * ky[2, j] + w[3] * ky[3, j])
            for i in range(k):
                for j in range(n):
                    V[i, j] += dt * (w[0] * kV[0, i, j] + w[1] * kV[1, i, j] + w[2] * kV[2, i, j]
                                     + w[3] * kV[3, i, j])
            t = t0 + (q * steps_per_orth + s + 1) * dt
        if not (np.all(np.isfinite(y)) and np.all(np.isfinite(V))):
            status = 3
            break
        Q, R = np.linalg.qr(np.ascontiguousarray(V.T))
        put2(V, Q.T)
        if q >= n_transient:
            accumulated[0] += steps_per_orth * dt
            for i in range(k):
                log_sum[i] += math.log(abs(R[i, i]))
            for i in range(k):
                running[q, i] = log_sum[i] / accumulated[0]
    return t, status


register_kernel(_benettin_impl, rhs=rhs_signature,
                jvp=lambda T: _nt.void(_nt.float64, _nt.float64[::1], _nt.float64[::1], T["args"], _nt.float64[::1]))


@njit(cache=True)
def _benettin_map_kernel_body(x, J, V, log_sum, tmp):
    """V <- J V for tangent rows V (k, n); helper of the map kernel."""
    k, n = V.shape
    for i in range(k):
        for a in range(n):
            s = 0.0
            for b in range(n):
                s += J[a, b] * V[i, b]
            tmp[i, a] = s
    put2(V, tmp)


def _benettin_map_impl(step, jac, x0, V0, args, n_iter, n_transient):
    n = x0.shape[0]
    k = V0.shape[0]
    x = x0.copy()
    xn = np.empty(n)
    V = V0.copy()
    J = np.empty((n, n))
    tmp = np.empty((k, n))
    log_sum = np.zeros(k)
    for it in range(n_iter):
        jac(x, args, J)
        _benettin_map_kernel_body(x, J, V, log_sum, tmp)
        step(x, args, xn)
        put(x, 0, xn)
        Q, R = np.linalg.qr(np.ascontiguousarray(V.T))
        put2(V, Q.T)
        if it >= n_transient:
            for i in range(k):
                log_sum[i] += math.log(abs(R[i, i]))
    return log_sum / max(n_iter - n_transient, 1), x


register_kernel(_benettin_map_impl, step=lambda T: _nt.void(_nt.float64[::1], T["args"], _nt.float64[::1]),
                jac=lambda T: _nt.void(_nt.float64[::1], T["args"], _nt.float64[:, ::1]))


@dataclass(frozen=True)
class LyapunovSpectrum:
    """Result of :func:`lyapunov_spectrum`.

    Attributes
    ----------
    exponents : ndarray (k,)
        Lyapunov exponents [1/s], largest first.
    times : ndarray (q,)
        Accumulation times [s] of the running estimates.
    running : ndarray (q, k)
        Running estimates [1/s] after each re-orthonormalisation (convergence check).
    y_final : ndarray (n,)
        State at the end.
    """

    exponents: np.ndarray
    times: np.ndarray
    running: np.ndarray
    y_final: np.ndarray

    @property
    def uncertainty(self) -> np.ndarray:
        """Standard error [1/s] of each exponent by batch means: the averaging time is cut into
        ``BATCHES`` equal blocks of whole re-orthonormalisation intervals, each block's exponent is
        its own log stretching over its own time, and the uncertainty is std(block exponents) /
        sqrt(blocks) (NaN with fewer than 2 intervals).  The blocks' mean is the exponent itself."""
        return batch_means_uncertainty(self.times, self.running)

    @property
    def change(self) -> np.ndarray:
        """Change [1/s] of each running estimate over the second half of the averaging time,
        |running[-1] - running[q // 2]| (:func:`second_half_change`)."""
        return second_half_change(self.running)

    @property
    def convergence(self) -> np.ndarray:
        """Relative change of each running estimate over the second half, ``change / |exponent|`` (inf
        for an exponent of exactly 0)."""
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(self.exponents != 0.0, self.change / np.abs(self.exponents), np.inf)

    @property
    def verdicts(self) -> list:
        """Per exponent: "positive" when it exceeds ``VERDICT_FACTOR`` uncertainties and has settled, "not
        positive", "not converged (moved X % over the second half)" or "undetermined" (see :func:`verdict`)."""
        return [verdict(lam, u, d) for lam, u, d in zip(self.exponents, self.uncertainty, self.change)]

    @property
    def sum(self) -> float:
        """Sum of the exponents [1/s] (mean phase-space contraction rate when k = n)."""
        return float(np.sum(self.exponents))

    def kaplan_yorke_dimension(self) -> float:
        """Kaplan-Yorke dimension j + sum_{i<=j} lambda_i / |lambda_{j+1}| [-]."""
        lam = np.sort(self.exponents)[::-1]
        c = np.cumsum(lam)
        j = int(np.sum(c >= 0.0))
        if j == 0:
            return 0.0
        if j == lam.size:
            return float(j)
        return float(j + c[j - 1] / abs(lam[j]))


#: blocks of the batch-means uncertainty of Benettin exponents
BATCHES = 10
#: an exponent is "positive" when it exceeds this many uncertainties (about a one-sided 2-sigma test)
VERDICT_FACTOR = 2.0
#: a verdict needs a settled estimate.  A "positive" exponent: its running value moved over the second
#: half of the record by at most this fraction of itself (Wolf's ``resolved`` uses the same 20 %,
#: ``WOLF_CONVERGED``).  A "not positive" one: by at most the larger of that and the band VERDICT_FACTOR x
#: uncertainty its verdict is judged against, since an exponent at 0 has no relative change and its running
#: value wanders by about one uncertainty (measured, change / band: Lorenz' flow direction at T = 20-500 s
#: 0.06-0.64, a harmonic oscillator at T = 7.7-50 s 0.11-0.25, Wolf on pure sines 0.03-0.69).
SETTLED = 0.2


def second_half_change(running) -> np.ndarray:
    """|running[-1] - running[q // 2]|: how far running estimates (q,) or (q, k) moved over the second half."""
    r = np.asarray(running, dtype=float)
    if r.shape[0] == 0:
        return np.full(r.shape[1:], np.nan)
    return np.abs(r[-1] - r[r.shape[0] // 2])


def verdict(exponent, uncertainty, change=None) -> str:
    """"positive" when ``exponent > VERDICT_FACTOR * uncertainty``, "not positive" otherwise,
    "undetermined" when the uncertainty is not finite; with ``change`` (how far the running estimate
    moved over the second half of the record, :func:`second_half_change`), "not converged (moved X % over
    the second half)" instead unless the estimate has settled: ``change <= SETTLED |exponent|`` for a
    positive one, ``change <= max(SETTLED |exponent|, VERDICT_FACTOR uncertainty)`` otherwise.

    >>> verdict(0.9, 0.05), verdict(0.01, 0.02), verdict(-1.0, 0.1), verdict(0.5, float("nan"))
    ('positive', 'not positive', 'not positive', 'undetermined')
    >>> verdict(0.9, 0.05, change=0.72), verdict(0.9, 0.05, change=0.1), verdict(0.001, 0.02, change=0.03)
    ('not converged (moved 80 % over the second half)', 'positive', 'not positive')
    >>> verdict(-0.5, 0.02, change=0.4)
    'not converged (moved 80 % over the second half)'
    """
    if not np.isfinite(uncertainty) or not np.isfinite(exponent):
        return "undetermined"
    positive = exponent > VERDICT_FACTOR * uncertainty
    if change is not None:
        limit = SETTLED * abs(exponent) if positive else max(SETTLED * abs(exponent), VERDICT_FACTOR * uncertainty)
        if not change <= limit:  # NaN: not settled either
            moved = (f"{100.0 * change / abs(exponent):.0f} %" if exponent != 0.0 and np.isfinite(change)
                     else f"by {change:.3g}")
            return f"not converged (moved {moved} over the second half)"
    return "positive" if positive else "not positive"


def batch_means_uncertainty(times, running, batches=BATCHES) -> np.ndarray:
    """Batch-means standard error [1/s] of exponents whose running estimates ``running`` (q, k) are
    given at accumulation times ``times`` (q,): the cumulative log stretching S = running * times is
    cut into ``min(batches, q)`` blocks of whole intervals; std of the block exponents / sqrt(blocks)."""
    times = np.asarray(times, dtype=float)
    running = np.asarray(running, dtype=float).reshape(times.size, -1)
    q, k = running.shape
    nb = min(int(batches), q)
    if nb < 2:
        return np.full(k, np.nan)
    S = np.vstack([np.zeros((1, k)), running * times[:, None]])
    T = np.concatenate([[0.0], times])
    edges = np.unique(np.linspace(0, q, nb + 1).round().astype(int))
    lam_b = (S[edges[1:]] - S[edges[:-1]]) / (T[edges[1:]] - T[edges[:-1]])[:, None]
    return np.std(lam_b, axis=0, ddof=1) / math.sqrt(lam_b.shape[0])


def _positive(key, value):
    v = float(value)
    if not (v > 0.0 and math.isfinite(v)):
        raise DynamicsInputError(f"{key} = {value!r} must be a finite number > 0")
    return v


class BenettinRun:
    """Benettin's method as an object that can be advanced, stopped, saved and resumed: everything the kernel
    carries from one orthonormalisation interval to the next (the scaled state z = y / scale, the tangent
    rows V, the log sums, the time accumulated and the running estimates) lives in its arrays, and the time
    is computed from the interval's index, so any sequence of :meth:`advance` calls -- and a
    :meth:`save` / :meth:`load` between them, in another process -- gives the bits of one call
    (``tests/test_tangent_directions.py``).  :func:`lyapunov_spectrum` is one :meth:`advance` over the whole
    record; the arguments are its own.

    ``V0`` (k, n), optional: initial tangent rows (orthonormalised here); default ``seed``'s random ones.
    """

    def __init__(self, rhs, y0, args=(), *, dt, t_orth=None, t_transient=0.0, n_exponents=None, jvp=None, t0=0.0,
                 seed=0, omega_max=None, frozen=None, scale=None, V0=None):
        if not hasattr(rhs, "py_func"):
            raise DynamicsInputError(f"rhs = {rhs!r} must be an @njit function rhs(t, y, args, dydt)")
        if jvp is not None and not hasattr(jvp, "py_func"):
            raise DynamicsInputError(f"jvp = {jvp!r} must be an @njit function jvp(t, y, v, args, out) or None")
        y0 = np.array(y0, dtype=np.float64, ndmin=1)
        if y0.ndim != 1 or not np.all(np.isfinite(y0)):
            raise DynamicsInputError(f"y0 (shape {y0.shape}) must be a 1-D array of finite numbers")
        n = y0.size
        keep = np.ones(n)
        if frozen is not None:
            idx = np.asarray(frozen, dtype=np.int64).ravel()
            if idx.size and (idx.min() < 0 or idx.max() >= n):
                raise DynamicsInputError(f"frozen = {list(idx)!r} must hold state indices between 0 and {n - 1}")
            keep[idx] = 0.0
        n_free = int(keep.sum())
        k = n_free if n_exponents is None else int(n_exponents)
        if not 1 <= k <= n_free:
            raise DynamicsInputError(f"n_exponents = {n_exponents!r} must be between 1 and the number of "
                                     f"state entries in the tangent space, {n_free}")
        dt = _positive("dt", dt)
        t_orth = 10 * dt if t_orth is None else _positive("t_orth", t_orth)
        if omega_max is not None:
            limit = stability_limit("rk4") / _positive("omega_max", omega_max)
            if dt > limit:
                raise DynamicsInputError(f"dt = {dt:g} s is beyond the RK4 stability limit {limit:g} s "
                                         f"for omega_max = {omega_max:g} rad/s")
        if t_transient < 0:
            raise DynamicsInputError(f"t_transient = {t_transient!r} must be >= 0")
        self.steps_per_orth = max(1, int(round(t_orth / dt)))
        self.n_transient = int(math.ceil(t_transient / (self.steps_per_orth * dt)))
        if V0 is None:
            G = np.random.default_rng(seed).standard_normal((n, k)) * keep[:, None]
        else:
            G = np.array(V0, dtype=np.float64, ndmin=2)
            if G.shape != (k, n) or not np.all(np.isfinite(G)):
                raise DynamicsInputError(f"V0 (shape {G.shape}) must hold {k} finite tangent rows of length {n}")
            G = G.T * keep[:, None]
        V = np.linalg.qr(G)[0].T.copy()
        V[:, keep == 0.0] = 0.0  # exactly zero (QR round-off)
        if scale is None:
            scale = np.ones(n)
        else:
            scale = np.array(scale, dtype=np.float64, ndmin=1)
            if scale.shape != (n,) or not np.all(np.isfinite(scale) & (scale > 0.0)):
                raise DynamicsInputError(f"scale (shape {scale.shape}) must hold {n} finite numbers > 0")
        self.rhs, self.jvp, self.args = rhs, jvp, args
        self.dt, self.t0, self.keep, self.scale = dt, float(t0), keep, scale
        self.kernel = specialise(_benettin_impl, rhs=rhs, jvp=no_jvp if jvp is None else jvp)
        self.z, self.V = y0 / scale, V
        self.log_sum, self.accumulated, self.running = np.zeros(k), np.zeros(1), np.full((0, k), np.nan)
        self.q = 0  # orthonormalisation intervals done
        self.t = float(t0)

    @property
    def y(self) -> np.ndarray:
        """The state now, in the rhs' units."""
        return self.z * self.scale

    @property
    def interval(self) -> float:
        """Re-orthonormalisation interval [s] (whole steps)."""
        return self.steps_per_orth * self.dt

    def advance(self, n_intervals, *, n_chunks=1, progress=None, observe=None):
        """Advance by ``n_intervals`` orthonormalisation intervals in at most ``n_chunks`` kernel calls (the
        bits do not depend on it); ``progress(fraction)`` after each call; ``observe(run)`` after every
        interval (the run then calls the kernel once an interval: :attr:`V`'s rows are the orthonormalised
        tangent vectors, :attr:`log_sum` the stretching so far).  A non-finite state or tangent vector raises
        :class:`IntegrationError`."""
        n_intervals = int(n_intervals)
        q_start, q_stop = self.q, self.q + n_intervals
        if self.running.shape[0] < q_stop:
            grown = np.full((q_stop, self.V.shape[0]), np.nan)
            grown[:self.running.shape[0]] = self.running
            self.running = grown
        stops = q_start + chunk_bounds(n_intervals, n_intervals if observe is not None else n_chunks)
        for q_begin, q_end in zip(stops[:-1], stops[1:]):
            t_end, status = self.kernel(self.z, self.V, self.keep, self.scale, self.args, self.t0, self.dt,
                                        self.steps_per_orth, int(q_begin), int(q_end), self.n_transient,
                                        self.jvp is None, self.log_sum, self.accumulated, self.running)
            self.t = float(t_end)
            if status != 0:
                raise IntegrationError(f"lyapunov_spectrum: non-finite state or tangent vector before t = "
                                       f"{t_end:.6g} s (dt = {self.dt:g} s too large?)", status=status, t_reached=t_end)
            self.q = int(q_end)
            if observe is not None:
                observe(self)
            if progress is not None:
                progress(float(q_end - q_start) / max(n_intervals, 1))

    def spectrum(self) -> "LyapunovSpectrum":
        """The exponents so far, largest first (the running estimates from the end of the transient)."""
        accumulated = float(self.accumulated[0])
        lam = self.log_sum / accumulated if accumulated > 0 else np.full(self.log_sum.shape, np.nan)
        order = np.argsort(lam)[::-1]
        n_orth = max(self.q - self.n_transient, 0)
        times = (np.arange(n_orth) + 1) * self.steps_per_orth * self.dt
        return LyapunovSpectrum(exponents=lam[order], times=times,
                                running=self.running[self.n_transient:self.q, order], y_final=self.y)

    #: what :meth:`save` keeps: the kernel's carried arrays and the settings that fix its bits
    _SAVED = ("z", "V", "log_sum", "accumulated", "running", "keep", "scale")

    def save(self, path) -> None:
        """Write the run's state to ``path`` (.npz) for :meth:`load` (the rhs, jvp and args are not saved:
        the caller gives them again)."""
        np.savez(path, q=self.q, t=self.t, t0=self.t0, dt=self.dt, steps_per_orth=self.steps_per_orth,
                 n_transient=self.n_transient, **{name: getattr(self, name) for name in self._SAVED})

    @classmethod
    def load(cls, path, rhs, args=(), *, jvp=None) -> "BenettinRun":
        """A run continued from :meth:`save`'s file, with the same ``rhs``, ``args`` and ``jvp``."""
        with np.load(path) as f:
            d = {key: f[key] for key in f.files}
        run = cls(rhs, d["z"] * d["scale"], args, dt=float(d["dt"]), t_orth=float(d["dt"]) * int(d["steps_per_orth"]),
                  n_exponents=d["V"].shape[0], jvp=jvp, t0=float(d["t0"]), scale=d["scale"], V0=None,
                  frozen=np.flatnonzero(d["keep"] == 0.0))
        run.steps_per_orth, run.n_transient = int(d["steps_per_orth"]), int(d["n_transient"])
        for name in cls._SAVED:
            setattr(run, name, np.ascontiguousarray(d[name]))
        run.q, run.t = int(d["q"]), float(d["t"])
        return run


def lyapunov_spectrum(rhs, y0, args=(), *, dt, t_total, t_orth=None, t_transient=0.0, n_exponents=None,
                      jvp=None, t0=0.0, seed=0, omega_max=None, frozen=None, scale=None, n_chunks=1,
                      progress=None):
    """Lyapunov spectrum of the flow ``dy/dt = rhs(t, y, args)`` by Benettin's method.

    Parameters
    ----------
    rhs : numba dispatcher
        ``rhs(t, y, args, dydt)`` (contract of :mod:`lubedyn.dynamics.integrators`).
    y0 : array_like (n,)
        Initial state (preferably already on the attractor; see ``t_transient``).
    dt : float
        RK4 step [s] for state and tangent vectors.
    t_total : float
        Averaging time [s] after the transient.
    t_orth : float, optional
        Re-orthonormalisation interval [s] (rounded to whole steps; default 10 dt).
    t_transient : float
        Time [s] integrated first whose stretching is discarded (aligns the tangent vectors).
    n_exponents : int, optional
        Number k of exponents (default n; k < n gives the k largest).
    jvp : numba dispatcher, optional
        ``jvp(t, y, v, args, out)`` writing J(t, y) v; forward differences of ``rhs`` if None.
    seed : int
        Seed of the random orthonormal initial tangent vectors.
    omega_max : float, optional
        Highest angular frequency [rad/s] of the system (e.g. sqrt(k / m) of
        the stiffest contact); ``dt`` beyond the RK4 stability limit 2.83 /
        omega_max is refused.
    frozen : sequence of int, optional
        State entries left out of the tangent space (their tangent components
        stay 0): memory (hysteresis) states whose rate switches
        discontinuously, see "Memory states" in the module docstring.  The
        exponents are then those of the other states with the memory shared
        by the reference and the perturbed trajectories; ``n_exponents`` is
        at most n - len(frozen).
    scale : array_like (n,), optional
        A natural perturbation size of each state entry (e.g. 1 um for a
        position, 1 rad/s for a speed): state and tangent vectors are
        integrated on z = y / scale, where one finite-difference step suits
        every entry (exponents do not change under a constant scaling, but
        forward differences on a state mixing micrometres and thousands of
        rad/s do; ``tests/test_bearing_lyapunov.py``).  Default: no scaling.
    n_chunks : int
        Number of kernel calls the run is cut into (at orthonormalisation intervals); the result is
        bit-identical for any number (``tests/test_lyapunov.py``).  Control returns to Python between
        them, for ``progress``.
    progress : callable, optional
        ``progress(fraction)`` after each chunk, with the fraction of the intervals done (ending at 1.0).

    Returns
    -------
    LyapunovSpectrum

    A run to be stopped and resumed, or watched after every interval, is a :class:`BenettinRun` (this
    function is one :meth:`BenettinRun.advance` over the transient and ``t_total``).
    """
    run = BenettinRun(rhs, y0, args, dt=dt, t_orth=t_orth, t_transient=t_transient, n_exponents=n_exponents,
                      jvp=jvp, t0=t0, seed=seed, omega_max=omega_max, frozen=frozen, scale=scale)
    t_total = _positive("t_total", t_total)
    n_orth = max(1, int(math.ceil(t_total / run.interval)))
    run.advance(n_orth + run.n_transient, n_chunks=n_chunks, progress=progress)
    return run.spectrum()


def spectrum_kernel_example(rhs, args, jvp=None):
    """``(kernel, example arguments)`` of :func:`lyapunov_spectrum`'s kernel for ``rhs`` and ``args``, for
    :func:`lubedyn.dynamics.specialise.compile_in_background` (the arguments have the types of its call)."""
    kernel = specialise(_benettin_impl, rhs=rhs, jvp=no_jvp if jvp is None else jvp)
    return kernel, (np.zeros(1), np.zeros((1, 1)), np.ones(1), np.ones(1), args, 0.0, 1.0, 1, 0, 1, 0, jvp is None,
                    np.zeros(1), np.zeros(1), np.zeros((1, 1)))


def lyapunov_spectrum_map(step, jac, x0, args=(), *, n_iter, n_transient=0, n_exponents=None, seed=0):
    """Lyapunov spectrum of a map ``x_{n+1} = step(x_n)`` [per iteration], largest first.

    ``step(x, args, out)`` writes g(x); ``jac(x, args, J)`` writes the n x n
    Jacobian Dg(x); both @njit.  QR re-orthonormalisation every iteration.
    """
    for key, f in (("step", step), ("jac", jac)):
        if not hasattr(f, "py_func"):
            raise DynamicsInputError(f"{key} = {f!r} must be an @njit function")
    x0 = np.array(x0, dtype=np.float64, ndmin=1)
    n = x0.size
    k = n if n_exponents is None else int(n_exponents)
    if not 1 <= k <= n:
        raise DynamicsInputError(f"n_exponents = {n_exponents!r} must be between 1 and the state size {n}")
    if int(n_iter) < 1 or int(n_transient) < 0:
        raise DynamicsInputError(f"n_iter = {n_iter!r} must be >= 1 and n_transient = {n_transient!r} >= 0")
    V0 = np.linalg.qr(np.random.default_rng(seed).standard_normal((n, k)))[0].T.copy()
    kernel = specialise(_benettin_map_impl, step=step, jac=jac)
    lam, _ = kernel(x0, V0, args, int(n_iter) + int(n_transient), int(n_transient))
    return np.sort(lam)[::-1]


# Rosenstein ------------------------------------------------------------------------------
def delay_embedding(x, dim, delay):
    """Delay vectors X_i = (x_i, x_{i+tau}, ..., x_{i+(m-1) tau}), shape (N - (m-1) tau, m)."""
    x = np.asarray(x, dtype=np.float64)
    M = x.size - (dim - 1) * delay
    return np.stack([x[e * delay:e * delay + M] for e in range(dim)], axis=1)


def nearest_neighbours(X, n_usable, theiler, chunk=2048):
    """Index of the nearest neighbour of each of the first ``n_usable`` rows of X, outside the Theiler window.

    Euclidean distance, ``|i - j| > theiler``, neighbours also among the first
    ``n_usable`` rows (so both can be followed).  A k-d tree
    (``scipy.spatial.cKDTree``) is queried for the ``2 theiler + 2`` nearest
    points, which always include one outside the window; exact duplicates
    (distance 0) are skipped.  -1 where none exists.
    """
    from scipy.spatial import cKDTree

    pts = X[:n_usable]
    tree = cKDTree(pts)
    k = int(min(2 * theiler + 3, n_usable))
    nn = np.full(n_usable, -1, dtype=np.int64)
    for start in range(0, n_usable, chunk):
        stop = min(start + chunk, n_usable)
        dist, idx = tree.query(pts[start:stop], k=k)
        dist = dist.reshape(stop - start, k)
        idx = idx.reshape(stop - start, k)
        ok = (np.abs(idx - np.arange(start, stop)[:, None]) > theiler) & (dist > 0.0) & (idx < n_usable)
        first = np.argmax(ok, axis=1)
        has = ok[np.arange(stop - start), first]
        nn[start:stop][has] = idx[np.arange(stop - start), first][has]
    return nn


@njit(cache=True)
def _rosenstein_divergence(X, nn, n_follow):
    """Mean log distance <ln d_i(k)>, k = 0..n_follow-1, over nearest-neighbour pairs (Rosenstein)."""
    dim = X.shape[1]
    sums = np.zeros(n_follow)
    counts = np.zeros(n_follow)
    for i in range(nn.shape[0]):
        j = nn[i]
        if j < 0:
            continue
        for kk in range(n_follow):
            d = 0.0
            for e in range(dim):
                diff = X[i + kk, e] - X[j + kk, e]
                d += diff * diff
            if d > 0.0:
                sums[kk] += 0.5 * math.log(d)
                counts[kk] += 1.0
    out = np.full(n_follow, np.nan)
    for kk in range(n_follow):
        if counts[kk] > 0:
            out[kk] = sums[kk] / counts[kk]
    return out


@dataclass(frozen=True)
class RosensteinResult:
    """Largest Lyapunov exponent from a time series.

    ``exponent`` [1/s]; ``times`` [s] and ``divergence`` (mean ln distance [-])
    are the curve whose slope over ``fit_range`` [s] gives it.  ``uncertainty``
    [1/s]: the spread of the slope over neighbouring fit windows
    (``window_slopes``, see :func:`largest_lyapunov_rosenstein`), or the
    slope's standard error if larger; ``verdict``: "positive" or "not positive" (the record alone;
    the guarded verdict is :func:`assess_largest_lyapunov`'s).
    """

    exponent: float
    times: np.ndarray
    divergence: np.ndarray
    fit_range: tuple
    uncertainty: float = float("nan")
    window_slopes: tuple = ()

    @property
    def verdict(self) -> str:
        """"positive" beyond ``VERDICT_FACTOR`` uncertainties, else "not positive" (see :func:`verdict`)."""
        return verdict(self.exponent, self.uncertainty)


def mean_period(x, dt):
    """Mean period [s] of a signal: 1 / (power-weighted mean frequency) (Rosenstein's Theiler window).
    A series without variation (:func:`series_shortfall`) has none: DynamicsInputError."""
    x = np.asarray(x, dtype=float)
    reason = series_shortfall(x)
    if reason:
        raise DynamicsInputError(f"x has {reason}: it has no mean period")
    x = x - np.mean(x)
    p = np.abs(np.fft.rfft(x)) ** 2
    f = np.fft.rfftfreq(x.size, dt)
    fm = np.sum(f[1:] * p[1:]) / np.sum(p[1:])
    return 1.0 / fm


#: fewest samples of a series any time-series exponent looks at
MIN_SERIES = 3


def series_shortfall(x) -> str:
    """Why the series ``x`` cannot give a time-series exponent at all ("" if it can): fewer than
    ``MIN_SERIES`` samples, non-finite values, or a constant series (its range at most 16 rounding units of
    its size: a delay embedding of it is one point, so no neighbour and no divergence).

    >>> import numpy as np
    >>> series_shortfall(np.full(500, 0.3))
    '500 samples of a constant (0.3): not computed, a constant series has no divergence to follow'
    >>> series_shortfall([1.0, 2.0]), series_shortfall(np.sin(np.arange(9.0)))
    ('2 samples: too short (at least 3)', '')
    """
    x = np.asarray(x, dtype=float)
    if x.ndim != 1:
        return f"shape {x.shape}: not a 1-D series"
    if x.size < MIN_SERIES:
        return f"{x.size} samples: too short (at least {MIN_SERIES})"
    if not np.all(np.isfinite(x)):
        return f"{int(np.count_nonzero(~np.isfinite(x)))} non-finite samples of {x.size}"
    if np.ptp(x) <= 16.0 * np.finfo(float).eps * float(np.max(np.abs(x))):
        return (f"{x.size} samples of a constant ({x[0]:.6g}): not computed, a constant series has no divergence "
                "to follow")
    return ""


def _rosenstein_record(x, dt, dim, delay, theiler, t_follow):
    """``(reason, theiler, n_follow)``: ``reason`` is "" when the record is long enough for Rosenstein's
    method, else why not (the neighbour search needs M - n_follow >= 2 theiler + 10 embedded points,
    M = N - (dim - 1) delay; a series that is constant or too short for anything: :func:`series_shortfall`)."""
    reason = series_shortfall(x)
    if reason:
        return reason, None, 0
    theiler = int(round(mean_period(x, dt) / dt)) if theiler is None else int(theiler)
    n_follow = int(round((t_follow if t_follow is not None else 0.2 * x.size * dt) / dt)) + 1
    M = x.size - (dim - 1) * delay
    if M - n_follow >= 2 * theiler + 10:
        return "", theiler, n_follow
    return (f"{x.size} samples: too short for dim = {dim}, delay = {delay}, theiler = {theiler}, "
            f"follow = {n_follow} samples (the delay embedding spans {(dim - 1) * delay} samples, the "
            f"neighbour search needs {2 * theiler + 10} more beyond the {n_follow} followed)"), theiler, n_follow


def rosenstein_shortfall(x, dt, *, dim, delay, theiler=None, t_follow=None) -> str:
    """Why the series ``x`` is too short for :func:`largest_lyapunov_rosenstein` with these
    settings ("" if it is long enough).  A record shorter than a few mean periods of the signal plus
    the embedding span cannot give an exponent; callers that meet such a record report this reason
    instead of a number.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.arange(500) * 1e-3
    >>> rosenstein_shortfall(np.sin(2 * np.pi * 2.0 * t), 1e-3, dim=6, delay=125)[:34]
    '500 samples: too short for dim = 6'
    >>> rosenstein_shortfall(np.sin(2 * np.pi * 50.0 * t), 1e-3, dim=3, delay=5)
    ''
    """
    x = np.asarray(x, dtype=np.float64)
    dt = _positive("dt", dt)
    return _rosenstein_record(x, dt, int(dim), int(delay), theiler, t_follow)[0]


def largest_lyapunov_rosenstein(x, dt, *, dim, delay, theiler=None, t_follow=None, fit_range=None):
    """Largest Lyapunov exponent [1/s] of a scalar series by Rosenstein's method.

    Parameters
    ----------
    x : array_like (N,)
        Uniformly sampled series.
    dt : float
        Sample interval [s] (1 for a map: exponent per iteration).
    dim, delay : int
        Embedding dimension m and delay tau [samples].
    theiler : int, optional
        Temporal exclusion window [samples] for neighbours (default: one mean period).
    t_follow : float, optional
        How long [s] neighbouring pairs are followed (default 20 % of the record).
    fit_range : (float, float), optional
        Time window [s] of the straight-line fit.  Default: where the curve
        has risen from 30 % to 70 % of the way from its start to its
        saturation level (median of the last quarter of ``t_follow``, which
        must therefore be long enough to saturate).  This skips the initial
        fast transient of the pairs (not yet along the most unstable
        direction: for Lorenz about 0.3 s) and the bend into saturation;
        check the curve (``times``, ``divergence``) for a new system.
    """
    x = np.asarray(x, dtype=np.float64)
    dt = _positive("dt", dt)
    dim, delay = int(dim), int(delay)
    if dim < 1 or delay < 1:
        raise DynamicsInputError(f"dim = {dim} and delay = {delay} must be >= 1")
    if x.ndim != 1 or not np.all(np.isfinite(x)):
        raise DynamicsInputError("x must be a 1-D array of finite numbers")
    reason, theiler, n_follow = _rosenstein_record(x, dt, dim, delay, theiler, t_follow)
    if reason:
        raise DynamicsInputError(f"x has {reason}")
    M = x.size - (dim - 1) * delay
    X = delay_embedding(x, dim, delay)
    nn = nearest_neighbours(X, M - n_follow, theiler)
    div = _rosenstein_divergence(X, nn, n_follow)
    times = np.arange(n_follow) * dt
    if fit_range is None:
        start = div[0]
        sat = np.nanmedian(div[3 * n_follow // 4:])
        rise = sat - start
        i0 = int(np.argmax(div >= start + 0.3 * rise))
        i1 = int(np.argmax(div >= start + 0.7 * rise))
        if not (rise > 0.0 and i1 > i0 + 1):
            raise DynamicsInputError(
                "largest_lyapunov_rosenstein: no divergence rise to fit; give fit_range or a longer t_follow")
        fit_range = (times[i0], times[i1])
    sel = (times >= fit_range[0]) & (times <= fit_range[1]) & np.isfinite(div)
    if np.count_nonzero(sel) < 2:
        raise DynamicsInputError(f"fit_range = {fit_range!r} holds fewer than 2 samples")
    slope = np.polyfit(times[sel], div[sel], 1)[0]
    u, slopes = _window_spread(times, div, fit_range, slope)
    return RosensteinResult(exponent=float(slope), times=times, divergence=div,
                            fit_range=(float(fit_range[0]), float(fit_range[1])), uncertainty=u,
                            window_slopes=slopes)


#: neighbouring fit windows of the uncertainty, as (start, end) in units of the fit window (0, 1)
FIT_WINDOW_SHIFTS = ((-0.25, 0.75), (0.25, 1.25), (0.0, 0.5), (0.5, 1.0), (-0.25, 1.25))
#: level resolution [-] of a mean log divergence curve: a signal without exponential separation moves
#: it by 0.2-0.8 (measured on pure sines, 500-8000 samples, periods 17-83 samples: nearest neighbours at
#: the rounding level drift apart linearly, and the nearest-neighbour choice biases the start low), so a
#: slope is resolved only to DIVERGENCE_LEVEL / (fit window length)
DIVERGENCE_LEVEL = 0.25


def _window_spread(times, div, fit_range, slope):
    """(uncertainty, slopes): the largest of (1) |slope - slope over a neighbouring window| (the window
    shifted by a quarter of its width either way, its halves, and widened by a quarter each side,
    kept within the followed time), (2) the slope's standard error from the fit residuals and (3)
    the level resolution ``DIVERGENCE_LEVEL / (t1 - t0)``.  A straight divergence curve (an
    exponential separation) gives the same slope over every window, a curve bending into saturation
    does not (1); a window over which the curve rises by less than a fraction of an e-fold cannot
    tell an exponential from a drift (3: a pure sine's +0.001-0.005 per sample stays below it)."""
    t0, t1 = fit_range
    width = t1 - t0
    ok = np.isfinite(div)
    slopes = []
    for a, b in FIT_WINDOW_SHIFTS:
        lo, hi = max(t0 + a * width, times[0]), min(t0 + b * width, times[-1])
        sel = ok & (times >= lo) & (times <= hi)
        if np.count_nonzero(sel) >= 3:
            slopes.append(float(np.polyfit(times[sel], div[sel], 1)[0]))
    sel = ok & (times >= t0) & (times <= t1)
    stderr = 0.0
    if np.count_nonzero(sel) > 2:
        tt, dd = times[sel], div[sel]
        res = dd - np.polyval(np.polyfit(tt, dd, 1), tt)
        stderr = float(np.sqrt(np.sum(res ** 2) / (tt.size - 2) / np.sum((tt - tt.mean()) ** 2)))
    spread = max((abs(s_ - slope) for s_ in slopes), default=float("nan"))
    level = DIVERGENCE_LEVEL / width if width > 0 else float("inf")
    return float(max(spread, stderr, level)), tuple(slopes)


def per_shaft_revolution(exponent, shaft_speed):
    """Convert exponents [1/s] to [1/rev]: lambda * 2 pi / Omega, ``shaft_speed`` Omega in rad/s."""
    shaft_speed = _positive("shaft_speed", shaft_speed)
    return np.asarray(exponent, dtype=float) * 2.0 * math.pi / shaft_speed


# Wolf ------------------------------------------------------------------------------------
#: Wolf et al.'s replacement settings: the angle limit [rad] of a replacement (their program's ANGLMX)
WOLF_ANGLE_MAX = 0.3
#: the replacement search radius is widened to 1, 2, ... WOLF_WIDEN times scale_max (their ZMULT) before
#: the angle limit is doubled (up to pi); with no candidate at all the evolved neighbour is kept
WOLF_WIDEN = 5
#: default scale_max and scale_min as fractions of the series' range max(x) - min(x)
WOLF_SCALE_MAX = 0.1
WOLF_SCALE_MIN = 1e-4
#: fewest evolution steps of a record (the batch-means uncertainty needs 10 blocks of 2 at least)
WOLF_MIN_STEPS = 20
#: "not resolved" when the running estimate changed by more than this fraction over the last half ...
WOLF_CONVERGED = SETTLED
#: ... or the uncertainty exceeds this fraction of the exponent
WOLF_RESOLVED = 0.5


@dataclass(frozen=True)
class WolfResult:
    """Largest Lyapunov exponent of a scalar series by Wolf et al.'s fixed-evolution-time algorithm
    (:func:`largest_lyapunov_wolf`).

    Attributes
    ----------
    exponent_bits : float
        lambda_1 [bits/s] (log base 2, Wolf et al.'s unit; bits per iteration for a map with dt = 1).
    times : ndarray (q,)
        Elapsed evolution time [s] after each evolution step.
    running : ndarray (q,)
        Running estimate [bits/s] after each step (the last is ``exponent_bits``).
    replacements : int
        Steps after which a replacement was due (the evolved separation had left
        [scale_min, scale_max]); the other steps keep the evolved neighbour, as Wolf et al.'s program does.
    poor_angle : int
        Of those, how many had to accept an angle above ``angle_max`` (found only after doubling the
        limit) or found no candidate at all and kept the evolved neighbour.
    uncertainty_bits : float
        Batch-means standard error [bits/s] of the exponent (:func:`batch_means_uncertainty` over
        ``BATCHES`` blocks of whole evolution steps).
    settings : dict
        dim, delay, evolve, theiler [samples], scale_min, scale_max [units of x], angle_max [rad].
    """

    exponent_bits: float
    times: np.ndarray
    running: np.ndarray
    replacements: int
    poor_angle: int
    uncertainty_bits: float
    settings: dict

    @property
    def exponent(self) -> float:
        """lambda_1 [1/s] (natural log): ``exponent_bits * ln 2``."""
        return self.exponent_bits * math.log(2.0)

    @property
    def uncertainty(self) -> float:
        """Uncertainty [1/s]."""
        return self.uncertainty_bits * math.log(2.0)

    @property
    def steps(self) -> int:
        """Evolution steps taken."""
        return int(self.times.size)

    @property
    def poor_angle_fraction(self) -> float:
        """Fraction of the due replacements that had to accept a poor angle (NaN without any)."""
        return self.poor_angle / self.replacements if self.replacements else float("nan")

    @property
    def convergence(self) -> float:
        """Relative change of the running estimate over the last half of the steps,
        |running[-1] - running[q // 2]| / |running[-1]| (inf when the estimate is 0)."""
        last, half = self.running[-1], self.running[self.running.size // 2]
        return float(abs(last - half) / abs(last)) if last != 0.0 else float("inf")

    @property
    def verdict(self) -> str:
        """"positive" beyond ``VERDICT_FACTOR`` uncertainties, else "not positive"; "not converged (moved X %
        over the second half)" where the running estimate has not settled (see :func:`verdict`).  The
        record alone: it calls white and AR(1) noise "positive"; the guarded verdict is
        :func:`assess_largest_lyapunov`'s."""
        return verdict(self.exponent_bits, self.uncertainty_bits, float(second_half_change(self.running)))

    @property
    def resolved(self) -> bool:
        """True when the uncertainty is at most ``WOLF_RESOLVED`` (half) of |exponent| and the running
        estimate changed by at most ``WOLF_CONVERGED`` (20 %) over the last half of the steps (the record
        alone: no surrogate or settings guard, see :func:`assess_largest_lyapunov`)."""
        return bool(np.isfinite(self.uncertainty_bits)
                    and self.uncertainty_bits <= WOLF_RESOLVED * abs(self.exponent_bits)
                    and self.convergence <= WOLF_CONVERGED)


def _wolf_record(x, dt, dim, delay, evolve, theiler):
    """``(reason, theiler)``: ``reason`` is "" when ``x`` is long enough for :func:`largest_lyapunov_wolf`,
    else why not.  The delay embedding takes (dim - 1) delay samples; the rest must hold
    ``WOLF_MIN_STEPS`` evolution steps and, after one step, neighbours outside the Theiler window (a
    series that is constant or too short for anything: :func:`series_shortfall`)."""
    reason = series_shortfall(x)
    if reason:
        return reason, None
    theiler = int(round(mean_period(x, dt) / dt)) if theiler is None else int(theiler)
    span = (dim - 1) * delay
    need = span + max(WOLF_MIN_STEPS * evolve + 1, evolve + 2 * theiler + 10)
    if x.size >= need:
        return "", theiler
    return (f"{x.size} samples: too short for Wolf's method with dim = {dim}, delay = {delay}, evolve = "
            f"{evolve}, theiler = {theiler}: it needs at least {need} (the delay embedding spans {span}, then "
            f"{WOLF_MIN_STEPS} evolution steps of {evolve} samples and neighbours outside the Theiler "
            "window)"), theiler


def wolf_shortfall(x, dt, *, dim, delay, evolve, theiler=None) -> str:
    """Why the series ``x`` is too short for :func:`largest_lyapunov_wolf` with these settings ("" if
    it is long enough); the text names the number of samples needed.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.arange(500) * 1e-3
    >>> wolf_shortfall(np.sin(2 * np.pi * 50.0 * t), 1e-3, dim=6, delay=100, evolve=20)[:49]
    "500 samples: too short for Wolf's method with dim"
    >>> wolf_shortfall(np.sin(2 * np.pi * 50.0 * t), 1e-3, dim=3, delay=5, evolve=5)
    ''
    """
    x = np.asarray(x, dtype=np.float64)
    dt = _positive("dt", dt)
    return _wolf_record(x, dt, int(dim), int(delay), int(evolve), theiler)[0]


@njit(cache=True)
def _wolf_ball(X, order, keys, p, r, n_use, target, theiler, smin, idx, d, dot, sep):
    """Candidates of a Wolf replacement within distance ``r`` of the fiducial point ``p`` = X[target]:
    embedded points i < n_use outside the Theiler window of ``target`` at distance d in [smin, r]
    (squared distance <= r^2, as a k-d tree's ball query); written to ``idx``, ``d`` and ``dot`` (the
    separation p - X[i] dotted with ``sep``), returns their count.  The search runs over the slab
    |X[i, 0] - p[0]| <= r of the points sorted by their first coordinate (``order``, ``keys``)."""
    m = X.shape[1]
    lo = np.searchsorted(keys, p[0] - r)
    hi = np.searchsorted(keys, p[0] + r, side="right")
    r2 = r * r
    low = max(smin, 1e-300)
    count = 0
    for k in range(lo, hi):
        i = order[k]
        if abs(i - target) <= theiler:
            continue
        s = 0.0
        for e in range(m):
            diff = p[e] - X[i, e]
            s += diff * diff
        if s > r2:
            continue
        dist = math.sqrt(s)
        if dist < low:
            continue
        c = 0.0
        for e in range(m):
            c += (p[e] - X[i, e]) * sep[e]
        idx[count] = i
        d[count] = dist
        dot[count] = c
        count += 1
    return count


@njit(cache=True)
def _wolf_better(th, d, i, th_best, d_best, i_best):
    """Whether candidate (angle ``th``, distance ``d``, index ``i``) beats the best so far: the smaller
    angle, then (equal angles: collinear separations whose |cos| rounds to 1 give exactly 0) the nearer
    point, then the earlier one -- an order that does not depend on how the candidates were found."""
    if th != th_best:
        return th < th_best
    if d != d_best:
        return d < d_best
    return i < i_best


@njit(cache=True)
def _wolf_walk(X, n_use, evolve, first, theiler, smin, smax, angle_max, widen):
    """Wolf et al.'s fixed-evolution-time walk (see :func:`largest_lyapunov_wolf`): ``(logs, kinds,
    steps)``, log2(L'/L) of each evolution step and each replacement's kind (0 kept: the evolved
    neighbour ``old`` still within [smin, smax]; 1 replaced within the angle limit; 2 replaced with a
    poorer angle, or no candidate: ``old`` kept).

    The replacement of the evolved neighbour of the evolved fiducial point X[ind]: candidates as in
    :func:`_wolf_ball`, searched at 1, 2 ... ``widen`` times smax; the one whose separation makes the
    smallest angle (|cos|, both orientations) with the evolved separation is taken below the angle
    limit; failing that, the limit is doubled (up to pi) over the widest radius' candidates; failing
    that the evolved neighbour is kept, or, when it has no evolution left, the nearest candidate."""
    m = X.shape[1]
    order = np.argsort(X[:n_use, 0], kind="mergesort")
    keys = X[order, 0].copy()
    nmax = n_use // evolve + 2
    logs = np.empty(nmax)
    kinds = np.empty(nmax, dtype=np.int64)
    idx = np.empty(n_use, dtype=np.int64)
    d = np.empty(n_use)
    dot = np.empty(n_use)
    th = np.empty(n_use)
    sep = np.empty(m)
    nlog = 0
    nkind = 0
    ind = 0
    nb = first
    while nb >= 0 and ind < n_use:
        di = 0.0
        df = 0.0
        for e in range(m):
            a = X[ind, e] - X[nb, e]
            di += a * a
            sep[e] = X[ind + evolve, e] - X[nb + evolve, e]
            df += sep[e] * sep[e]
        di = math.sqrt(di)
        df = math.sqrt(df)
        if df <= 0.0 or di <= 0.0:
            break
        logs[nlog] = math.log2(df / di)
        nlog += 1
        ind += evolve
        if ind >= n_use:
            break
        old = nb + evolve
        if smin <= df <= smax and old < n_use:
            nb = old
            kinds[nkind] = 0
            nkind += 1
            continue
        p = X[ind]
        count = 0
        chosen = -1
        for zmult in range(1, widen + 1):
            count = _wolf_ball(X, order, keys, p, zmult * smax, n_use, ind, theiler, smin, idx, d, dot, sep)
            if count == 0:
                continue
            best = 0
            for c in range(count):
                th[c] = math.acos(min(1.0, abs(dot[c]) / (d[c] * df)))
                if _wolf_better(th[c], d[c], idx[c], th[best], d[best], idx[best]):
                    best = c
            if th[best] < angle_max:
                chosen = idx[best]
                break
        if chosen >= 0:
            nb = chosen
            kinds[nkind] = 1
            nkind += 1
            continue
        kind = 2
        limit = 2.0 * angle_max
        while count > 0 and limit < math.pi and chosen < 0:
            for zmult in range(1, widen + 1):
                best = -1
                for c in range(count):
                    if d[c] <= zmult * smax and (best < 0 or _wolf_better(th[c], d[c], idx[c], th[best], d[best],
                                                                           idx[best])):
                        best = c
                if best >= 0 and th[best] < limit:
                    chosen = idx[best]
                    break
            limit *= 2.0
        if chosen < 0:
            if old < n_use:
                chosen = old
            elif count > 0:
                best = 0
                for c in range(count):
                    if d[c] < d[best] or (d[c] == d[best] and idx[c] < idx[best]):
                        best = c
                chosen = idx[best]
        nb = chosen
        kinds[nkind] = kind
        nkind += 1
    return logs[:nlog].copy(), kinds[:nkind].copy()


def _wolf_first(X, n_use, theiler, smin):
    """Nearest neighbour of embedded point 0 among points i < n_use, i > theiler, at distance >= smin."""
    d = np.linalg.norm(X[:n_use] - X[0], axis=1)
    d[:theiler + 1] = np.inf
    d[d < max(smin, 1e-300)] = np.inf
    j = int(np.argmin(d))
    return j if np.isfinite(d[j]) else -1


def largest_lyapunov_wolf(x, dt, *, dim, delay, evolve, theiler=None, scale_min=None, scale_max=None,
                          angle_max=WOLF_ANGLE_MAX):
    """Largest Lyapunov exponent of a scalar series by Wolf et al.'s fixed-evolution-time algorithm.

    Wolf, Swift, Swinney & Vastano, "Determining Lyapunov exponents from a time series", Physica D 16
    (1985) 285, section 5 and the fixed-evolution-time program of their appendix B: delay vectors
    X_i = (x_i, x_{i+tau}, ..., x_{i+(m-1)tau}); start from X_0 and its nearest neighbour (outside the
    Theiler window, at least ``scale_min`` away); follow both for ``evolve`` samples and add
    log2(L'/L) of the separation's growth; then keep the evolved neighbour if its separation L' is
    still within [scale_min, scale_max], else replace it by the point near the evolved fiducial point
    whose separation is closest in orientation to the evolved one (see :func:`_wolf_walk`:
    angle limit ``angle_max``, search radius widened up to 5 scale_max, then the angle limit doubled);
    repeat along the record.  lambda_1 = sum log2(L'/L) / (steps x evolve x dt) [bits/s]; times ln 2
    it is in 1/s (``WolfResult.exponent``).

    Parameters
    ----------
    x : array_like (N,)
        Uniformly sampled series.
    dt : float
        Sample interval [s] (1 for a map: bits per iteration).
    dim, delay : int
        Embedding dimension m and delay tau [samples].
    evolve : int
        Evolution time between replacements [samples] (Wolf et al.'s EVOLV).
    theiler : int, optional
        Neighbours closer in time than this [samples] are not used (default: one mean period,
        :func:`mean_period`; Wolf et al.'s program excludes 10 samples).
    scale_min, scale_max : float, optional
        Smallest and largest admissible separation [units of x] (their SCALMN, SCALMX): below
        ``scale_min`` noise (or round-off) dominates, beyond ``scale_max`` the separation no longer
        probes the local, linearised flow.  Defaults ``WOLF_SCALE_MIN`` = 1e-4 and ``WOLF_SCALE_MAX``
        = 0.1 of the series' range.
    angle_max : float
        Angle limit [rad] of a replacement (their ANGLMX, 0.3).

    Returns
    -------
    WolfResult
        exponent in bits/s and 1/s, the running estimate, replacement counts, batch-means uncertainty,
        ``verdict`` and ``resolved`` (see :class:`WolfResult`).

    Raises
    ------
    DynamicsInputError
        Bad settings, or a record too short (:func:`wolf_shortfall` says how many samples are needed).
    """
    x = np.asarray(x, dtype=np.float64)
    dt = _positive("dt", dt)
    dim, delay, evolve = int(dim), int(delay), int(evolve)
    if dim < 1 or delay < 1 or evolve < 1:
        raise DynamicsInputError(f"dim = {dim}, delay = {delay} and evolve = {evolve} must be >= 1")
    if x.ndim != 1 or not np.all(np.isfinite(x)):
        raise DynamicsInputError("x must be a 1-D array of finite numbers")
    if not 0.0 < angle_max < math.pi:
        raise DynamicsInputError(f"angle_max = {angle_max!r} must be in (0, pi) rad")
    reason, theiler = _wolf_record(x, dt, dim, delay, evolve, theiler)
    if reason:
        raise DynamicsInputError(f"x has {reason}")
    extent = float(np.ptp(x))
    smax = WOLF_SCALE_MAX * extent if scale_max is None else _positive("scale_max", scale_max)
    smin = WOLF_SCALE_MIN * extent if scale_min is None else float(scale_min)
    if not 0.0 <= smin < smax:
        raise DynamicsInputError(f"scale_min = {smin:g} must be >= 0 and < scale_max = {smax:g}")
    X = delay_embedding(x, dim, delay)
    n_use = X.shape[0] - evolve  # points whose evolution lies within the record
    logs, kinds = _wolf_walk(X, n_use, evolve, _wolf_first(X, n_use, theiler, smin), theiler, smin, smax,
                             float(angle_max), WOLF_WIDEN)
    if len(logs) < 2:
        raise DynamicsInputError(f"largest_lyapunov_wolf: only {len(logs)} evolution step(s) possible "
                                 f"(no neighbour of X_0 at >= scale_min = {smin:g} outside the Theiler window?)")
    times = (np.arange(len(logs)) + 1) * evolve * dt
    running = np.cumsum(logs) / times
    settings = {"dim": dim, "delay": delay, "evolve": evolve, "theiler": theiler, "scale_min": smin,
                "scale_max": smax, "angle_max": float(angle_max)}
    return WolfResult(exponent_bits=float(running[-1]), times=times, running=running,
                      replacements=int(np.count_nonzero(kinds > 0)), poor_angle=int(np.count_nonzero(kinds == 2)),
                      uncertainty_bits=float(batch_means_uncertainty(times, running)[0]), settings=settings)


# Guards of a time-series exponent -----------------------------------------------------------------------
#: false nearest neighbours (Kennel, Brown & Abarbanel 1992): a neighbour is false in dimension d when the
#: added coordinate separates it by more than FNN_RTOL times its distance in d dimensions ...
FNN_RTOL = 15.0
#: ... or its distance in d + 1 dimensions exceeds FNN_ATOL standard deviations of the series
FNN_ATOL = 2.0
#: the minimum embedding dimension is the first whose fraction of false neighbours is below this
FNN_THRESHOLD = 0.01
#: highest dimension the false-neighbour search tries
FNN_MAX_DIM = 10


def autocorrelation_delay(x) -> int:
    """Embedding delay [samples]: the first zero crossing of the autocorrelation of ``x`` (at least 1;
    a tenth of the record when it never crosses zero)."""
    x = np.asarray(x, dtype=float) - np.mean(x)
    n = x.size
    f = np.fft.rfft(x, 2 * n)
    ac = np.fft.irfft(f * np.conj(f))[:n]
    crossing = np.flatnonzero(ac <= 0.0)
    return max(1, int(crossing[0]) if crossing.size else n // 10)


@njit(cache=True)
def _nearest_outside(X, ref, theiler):
    """(index, squared distance) of the nearest row of X to each row ``ref[i]`` with |index - ref[i]| >
    theiler and a distance > 0 (brute force; -1 and inf where none)."""
    n, d = X.shape
    idx = np.full(ref.size, -1, dtype=np.int64)
    best = np.full(ref.size, np.inf)
    for a in range(ref.size):
        i = ref[a]
        for j in range(n):
            if abs(j - i) <= theiler:
                continue
            s = 0.0
            for e in range(d):
                diff = X[i, e] - X[j, e]
                s += diff * diff
                if s >= best[a]:
                    break
            if 0.0 < s < best[a]:
                best[a] = s
                idx[a] = j
    return idx, best


#: the delay's search: lags up to this fraction of the record, histogram bins of the mutual information
MI_MAX_LAG = 0.1
MI_BINS = 16


def mutual_information_delay(x) -> int:
    """Embedding delay [samples]: the first local minimum of the time-delayed mutual information of ``x``
    (Fraser & Swinney, Phys. Rev. A 33 (1986) 1134), from ``MI_BINS`` (16) equally spaced bins over the
    range, lags 1 .. ``MI_MAX_LAG`` (10 %) of the record; :func:`autocorrelation_delay` when it has no
    minimum there.  Lorenz x at 0.01 (sigma 10, rho 28, beta 8/3): 16 samples; white noise: 1-3."""
    x = np.asarray(x, dtype=float)
    lo, hi = float(np.min(x)), float(np.max(x))
    b = np.minimum((MI_BINS * (x - lo) / (hi - lo)).astype(np.int64), MI_BINS - 1) if hi > lo else np.zeros(x.size, np.int64)
    prev = None
    for lag in range(1, max(2, int(MI_MAX_LAG * x.size))):
        joint = np.bincount(b[:-lag] * MI_BINS + b[lag:], minlength=MI_BINS * MI_BINS).reshape(MI_BINS, MI_BINS)
        p = joint / joint.sum()
        px, py = p.sum(axis=1), p.sum(axis=0)
        nz = p > 0
        mi = float(np.sum(p[nz] * np.log(p[nz] / np.outer(px, py)[nz])))
        if prev is not None and mi > prev:
            return lag - 1
        prev = mi
    return autocorrelation_delay(x)


@dataclass(frozen=True)
class FalseNeighbours:
    """Result of :func:`false_nearest_neighbours`: ``dims`` (1 .. the minimum, or max_dim) and
    ``fractions`` of false nearest neighbours in each; ``minimum_dim`` the first dimension with a fraction below
    ``FNN_THRESHOLD`` (None when none up to ``max_dim``)."""

    dims: np.ndarray
    fractions: np.ndarray
    minimum_dim: int | None


def false_nearest_neighbours(x, delay, *, max_dim=FNN_MAX_DIM, theiler=None, rtol=FNN_RTOL, atol=FNN_ATOL,
                             threshold=FNN_THRESHOLD, max_points=1000) -> FalseNeighbours:
    """Minimum embedding dimension of ``x`` by false nearest neighbours (Kennel, Brown & Abarbanel, Phys.
    Rev. A 45 (1992) 3403).

    For d = 1 .. ``max_dim``: each delay vector of dimension d (delay ``delay`` samples) gets its nearest
    neighbour outside the Theiler window (``theiler`` samples, default one mean period in samples,
    :func:`mean_period` with dt = 1); the pair is false when adding the (d+1)-th coordinate separates it
    by more than ``rtol`` (15) times its distance R_d (their criterion 1), or when its distance in d + 1
    dimensions exceeds ``atol`` (2) standard deviations of ``x`` (criterion 2, which marks noise).  The
    first d with a fraction below ``threshold`` is the minimum embedding dimension, where the search
    stops (``fractions`` end there).  At most
    ``max_points`` evenly spaced reference points are tested (all points are candidate neighbours).

    Measured (tests/test_lyapunov_guards.py, 1,000 reference points): Lorenz x (5,000 samples at 0.01,
    delay 17 samples) false fractions 0.989, 0.059, 0.000 for d = 1, 2, 3: minimum 3; Henon x (delay 1)
    0.74, 0.00: 2; two incommensurate sines (delay 26 of 0.05) 0.99, 0.56, 0.03, 0.00: 4; white noise
    and AR(1) noise (phi 0.95) fall to 15-17 % at d = 4-5 and rise again (criterion 2): no minimum up to
    10.  Lorenz-96 (10 sites) coordinates: no minimum up to 10 with 5,000 samples."""
    x = np.asarray(x, dtype=np.float64)
    reason = series_shortfall(x)
    if reason:
        raise DynamicsInputError(f"x has {reason}")
    delay, max_dim = int(delay), int(max_dim)
    if delay < 1 or max_dim < 1:
        raise DynamicsInputError(f"delay = {delay} and max_dim = {max_dim} must be >= 1")
    theiler = int(round(mean_period(x, 1.0))) if theiler is None else int(theiler)
    sd = float(np.std(x))
    dims, fractions = [], []
    minimum = None
    for d in range(1, max_dim + 1):
        M = x.size - d * delay  # vectors that also have their (d+1)-th coordinate
        if M < 2 * theiler + 12:
            break
        X = delay_embedding(x[:M + (d - 1) * delay], d, delay)
        nxt = np.ascontiguousarray(x[d * delay:d * delay + M])
        ref = np.unique(np.linspace(0, M - 1, min(max_points, M)).round().astype(np.int64))
        j, r2 = _nearest_outside(X, ref, theiler)
        has = j >= 0
        if not np.any(has):
            break
        i, j, r = ref[has], j[has], np.sqrt(r2[has])
        extra = np.abs(nxt[i] - nxt[j])
        false = (extra > rtol * r) | (np.sqrt(r ** 2 + extra ** 2) > atol * sd)
        dims.append(d)
        fractions.append(float(np.mean(false)))
        if fractions[-1] < threshold:
            minimum = d
            break
    return FalseNeighbours(dims=np.asarray(dims), fractions=np.asarray(fractions), minimum_dim=minimum)


#: surrogates of the noise test: their number (with the series outside all of them, a two-sided rank
#: test at p = 2 / (n + 1) = 0.1) ...
N_SURROGATES = 19
#: ... and the z score |e - mean(surrogates)| / std(surrogates) the series' estimate must reach as well
SURROGATE_Z = 3.0
#: disjoint windows of the uncertainty
WINDOWS = 4
#: "converged" when the windows' standard error is at most this fraction of |estimate|
WINDOW_RESOLVED = 0.25
#: "insensitive to the settings" when every estimate of the settings grid is within this fraction of the
#: central estimate
SETTINGS_TOLERANCE = 0.35


@dataclass(frozen=True)
class LyapunovAssessment:
    """Result of :func:`assess_largest_lyapunov`: an estimate of the largest exponent of a series and
    the guards that decide whether it means anything.

    Attributes
    ----------
    method : str
        "wolf" or "rosenstein".
    exponent : float
        Estimate [1/s] on the whole record (or the mean over members) with the chosen settings.
    result : WolfResult or RosensteinResult
        The estimator's own result on the whole record (its ``verdict`` and ``resolved`` are those of the
        record alone: no guard).
    settings : dict
        dim, delay, evolve [samples] used; ``fnn_dim``: the false-neighbour minimum dimension (None:
        none up to ``FNN_MAX_DIM``).
    false_neighbours : FalseNeighbours
    surrogate_exponents : ndarray (n,)
        Estimates [1/s] on the surrogates (NaN where the estimator refused one).
    surrogate_z : float
        (exponent - mean) / std of the surrogate estimates.
    distinguishable : bool
        The estimate lies outside all surrogate estimates and |surrogate_z| >= ``SURROGATE_Z``.
    grid : dict
        Settings (dim, delay, evolve) -> estimate [1/s] over the one-at-a-time grid.
    settings_spread : float
        max |e - median| / max(|median|, 2 u) over the grid's estimates and the central one (e); u enters
        only for an estimate that is not positive.
    insensitive : bool
        ``settings_spread <= settings_tolerance`` and the dimension is at least the false-neighbour minimum
        (the grid leaves out dimensions below that minimum).
    window_exponents : ndarray (K,)
        Estimates [1/s] of the disjoint windows (or of the members).
    uncertainty : float
        Standard error [1/s]: std(window estimates) / sqrt(K).
    converged : bool
        The uncertainty is finite, at most ``WINDOW_RESOLVED |exponent|`` for a positive estimate, and for
        Wolf the running estimate settled.
    verdict : str
        "positive" / "not positive" when every guard passes; else the first failed guard:
        "not distinguishable from its surrogates (linear noise)", "depends on the embedding settings
        (...)", "not converged (...)".
    """

    method: str
    exponent: float
    result: object
    settings: dict
    false_neighbours: FalseNeighbours
    surrogate_exponents: np.ndarray
    surrogate_z: float
    distinguishable: bool
    grid: dict
    settings_spread: float
    insensitive: bool
    window_exponents: np.ndarray
    uncertainty: float
    converged: bool
    verdict: str

    @property
    def resolved(self) -> bool:
        """True when distinguishable from its surrogates, insensitive to the settings and converged."""
        return bool(self.distinguishable and self.insensitive and self.converged)


#: the settings grid scales delay and evolution time by these factors (one at a time)
SETTINGS_FACTORS = (2.0 / 3.0, 1.5)


def _around(n):
    """``n`` [samples] scaled by ``SETTINGS_FACTORS``, rounded, at least 1, and one sample away at least."""
    lo = min(max(1, int(round(n * SETTINGS_FACTORS[0]))), max(1, n - 1))
    hi = max(int(round(n * SETTINGS_FACTORS[1])), n + 1)
    return [v for v in (lo, hi) if v != n]


def _estimate(method, x, dt, dim, delay, evolve, theiler, options):
    """Exponent [1/s] of one series, or NaN when the estimator refuses it (too short, no rise)."""
    try:
        if method == "wolf":
            return largest_lyapunov_wolf(x, dt, dim=dim, delay=delay, evolve=evolve, theiler=theiler, **options)
        return largest_lyapunov_rosenstein(x, dt, dim=dim, delay=delay, theiler=theiler, **options)
    except DynamicsInputError as exc:
        logger.debug("estimate refused (dim %d, delay %d, evolve %s): %s", dim, delay, evolve, exc)
        return None


def _value(res):
    return float("nan") if res is None else float(res.exponent)


def assess_largest_lyapunov(x, dt, *, method="wolf", dim=None, delay=None, evolve=None, theiler=None,
                            members=None, n_surrogates=N_SURROGATES, surrogate="iaaft", windows=WINDOWS,
                            settings_tolerance=SETTINGS_TOLERANCE, seed=0, **options) -> LyapunovAssessment:
    """Largest Lyapunov exponent of the series ``x`` by Wolf's or Rosenstein's method, with the guards
    that tell chaos from noise and from the settings.

    1. Noise: ``n_surrogates`` surrogates of ``x`` (IAAFT, Schreiber & Schmitz 1996, or phase-randomised,
       Theiler et al. 1992: :mod:`lubedyn.dynamics.surrogates`, seeded by ``seed``) get the same estimate;
       they are made of the series' first ``fast_length(N)`` samples (:func:`~lubedyn.dynamics.surrogates.fast_length`:
       no prime factor above 31, at most 0.6 % fewer from 2,000 samples up), which keeps their FFTs fast.
       The series is "distinguishable from noise" when its estimate is outside all of theirs (a two-sided
       rank test, p = 2 / (n + 1)) and |z| >= ``SURROGATE_Z`` (3) with z = (e - mean) / std of theirs.
    2. Settings: the minimum embedding dimension by false nearest neighbours
       (:func:`false_nearest_neighbours`) must not exceed ``dim``, and the estimate with dim - 1, dim + 1,
       delay x 2/3 and 3/2 (and for Wolf evolve x 2/3 and 3/2) must each be within ``settings_tolerance``
       (35 %) of the median of them and the central one (of 2 uncertainties where that is larger: an
       estimate at 0).
    3. Convergence: the estimate over ``windows`` (4) disjoint windows of the record (or over ``members``,
       independent records of the same system, when given) gives the uncertainty std / sqrt(K); it must be
       at most ``WINDOW_RESOLVED`` (25 %) of a positive estimate, and Wolf's running estimate must have
       settled (moved at most ``SETTLED`` = 20 % over the second half, or 2 uncertainties for an estimate
       that is not positive).

    With ``members`` the surrogates, the false neighbours and the settings grid are those of ``x`` (the
    first member); the estimate and its uncertainty are the members' mean and std / sqrt(K).

    The verdict is "positive" (estimate beyond ``VERDICT_FACTOR`` uncertainties) or "not positive" only
    when all three pass; otherwise it names the first guard that failed, in the order above.

    Defaults: ``delay`` the first minimum of the mutual information (:func:`mutual_information_delay`), ``dim``
    the false-neighbour minimum (3 when there is none up to ``FNN_MAX_DIM``), ``evolve`` = ``delay``.
    ``options`` go to the estimator (scale_min, scale_max, angle_max for Wolf; t_follow, fit_range for
    Rosenstein).  Cost: 1 + n_surrogates + 6 (4 for Rosenstein) + windows estimates, e.g. 30 Wolf runs.

    Measured (tests/test_lyapunov_guards.py, Wolf, 19 IAAFT surrogates, 4 windows): the module's section
    "Guards of a time-series exponent" gives the numbers on Henon, Lorenz, Lorenz-96, two incommensurate
    sines, white and AR(1) noise and chaos on a large periodic orbit: Henon and Lorenz resolved
    "positive" (within 5 % and 20 % of the published values), the two incommensurate sines resolved
    "not positive", every other one not resolved.

    Raises
    ------
    DynamicsInputError
        Bad method, surrogate kind, counts or tolerance, or the estimator's own refusal of the whole
        record (too short, no divergence rise); refusals of a surrogate, window or grid setting give NaN.
    """
    from .surrogates import KINDS, fast_length

    if method not in ("wolf", "rosenstein"):
        raise DynamicsInputError(f"method = {method!r}: must be 'wolf' or 'rosenstein'")
    if surrogate not in KINDS:
        raise DynamicsInputError(f"surrogate = {surrogate!r}: must be one of {sorted(KINDS)}")
    x = np.asarray(x, dtype=np.float64)
    reason = series_shortfall(x)
    if reason:
        raise DynamicsInputError(f"x has {reason}")
    dt = _positive("dt", dt)
    if int(n_surrogates) < 2 or int(windows) < 2:
        raise DynamicsInputError(f"n_surrogates = {n_surrogates!r} and windows = {windows!r} must be >= 2")
    if not settings_tolerance > 0.0:
        raise DynamicsInputError(f"settings_tolerance = {settings_tolerance!r}: must be > 0")
    delay = mutual_information_delay(x) if delay is None else int(delay)
    theiler = int(round(mean_period(x, dt) / dt)) if theiler is None else int(theiler)
    fnn = false_nearest_neighbours(x, delay, theiler=theiler)
    dim = (fnn.minimum_dim or 3) if dim is None else int(dim)
    evolve = (delay if evolve is None else int(evolve)) if method == "wolf" else None
    res = _estimate(method, x, dt, dim, delay, evolve, theiler, options)
    if res is None:  # raise the estimator's own error for the whole record
        if method == "wolf":
            largest_lyapunov_wolf(x, dt, dim=dim, delay=delay, evolve=evolve, theiler=theiler, **options)
        else:
            largest_lyapunov_rosenstein(x, dt, dim=dim, delay=delay, theiler=theiler, **options)
    e0 = float(res.exponent)
    # 3. windows or members
    if members is not None:
        series = [x] + [np.asarray(m, dtype=np.float64) for m in members]
        win = np.array([_value(_estimate(method, s, dt, dim, delay, evolve, theiler, options)) for s in series])
        e_main = float(np.nanmean(win))
    else:
        edges = np.linspace(0, x.size, int(windows) + 1).round().astype(int)
        win = np.array([_value(_estimate(method, x[a:b], dt, dim, delay, evolve, theiler, options))
                        for a, b in zip(edges[:-1], edges[1:])])
        e_main = e0
    ok = np.isfinite(win)
    u = float(np.std(win[ok], ddof=1) / math.sqrt(ok.sum())) if ok.sum() >= 2 else float("nan")
    positive = bool(np.isfinite(u) and e_main > VERDICT_FACTOR * u)
    # an estimate at 0 has no relative size: it is judged against its resolution VERDICT_FACTOR u, as
    # :func:`verdict` judges a "not positive" running estimate
    resolution = VERDICT_FACTOR * u if np.isfinite(u) and not positive else 0.0
    settled = True
    if method == "wolf":
        change = float(second_half_change(res.running)) * math.log(2.0)  # [1/s]
        settled = bool(change <= max(SETTLED * abs(res.exponent), resolution))
    converged = bool(np.isfinite(u) and (u <= WINDOW_RESOLVED * abs(e_main) or not positive) and settled)
    # 2. settings
    grid = {}
    variants = [(dim - 1, delay, evolve), (dim + 1, delay, evolve)] + [(dim, d, evolve) for d in _around(delay)]
    if method == "wolf":
        variants += [(dim, delay, ev) for ev in _around(evolve)]
    lowest_dim = fnn.minimum_dim or 1  # dimensions that do not unfold the series are no setting to compare with
    for m, d, ev in variants:
        if m >= lowest_dim and (m, d, ev) != (dim, delay, evolve):
            grid[(m, d, ev)] = _value(_estimate(method, x, dt, m, d, ev, theiler, options))
    vals = np.array(list(grid.values()) + [e0])
    plateau = float(np.median(vals)) if np.all(np.isfinite(vals)) else float("nan")
    scale = max(abs(plateau), resolution) if np.isfinite(plateau) else 0.0
    spread = float(np.max(np.abs(vals - plateau)) / scale) if scale > 0.0 and vals.size > 1 else float("inf")
    under = fnn.minimum_dim is None or dim < fnn.minimum_dim
    if resolution > 0.0:  # "not positive": insensitive when no setting of the grid gives a positive estimate
        insensitive = bool(np.all(np.isfinite(vals)) and np.max(vals) <= resolution and not under)
    else:
        insensitive = bool(np.isfinite(spread) and spread <= settings_tolerance and not under)
    # 1. surrogates
    # of the first fast_length(N) samples: an N with a large prime factor sends every FFT of the IAAFT
    # iteration through Bluestein's algorithm (10-15 x slower); fast_length drops at most 0.6 % of them
    surr = KINDS[surrogate](x[:fast_length(x.size)], int(n_surrogates), seed)
    se = np.array([_value(_estimate(method, s, dt, dim, delay, evolve, theiler, options)) for s in surr])
    good = se[np.isfinite(se)]
    if good.size >= 2:
        sd = float(np.std(good, ddof=1))
        z = (e0 - float(np.mean(good))) / sd if sd > 0 else math.copysign(float("inf"), e0 - float(np.mean(good)))
        outside = bool(e0 > good.max() or e0 < good.min())
        distinguishable = bool(outside and abs(z) >= SURROGATE_Z and good.size >= int(n_surrogates) // 2)
    else:
        z, distinguishable = float("nan"), False
    if not distinguishable:
        v = (f"not distinguishable from its surrogates (linear noise): {e0:.4g} 1/s against "
             f"{np.mean(good) if good.size else float('nan'):.4g} +- "
             f"{np.std(good, ddof=1) if good.size >= 2 else float('nan'):.2g} over {good.size} {surrogate} surrogates, "
             f"z = {z:.2g}")
    elif not insensitive:
        refused = [k for k, v in grid.items() if not np.isfinite(v)]
        why = (f"the false-neighbour minimum dimension is {fnn.minimum_dim or f'above {FNN_MAX_DIM}'}, dim = {dim}"
               if under else f"the estimator refused (dim, delay, evolve) = {refused}" if refused
               else f"estimates {np.min(vals):.4g}-{np.max(vals):.4g} 1/s: above the resolution {resolution:.2g} "
               f"(2 uncertainties) of an estimate that is not positive" if resolution > 0.0 else f"estimates {np.nanmin(vals):.4g}-{np.nanmax(vals):.4g} 1/s, median {plateau:.4g}, "
               f"over dim +-1, delay and evolve x 2/3, 3/2: {spread:.0%} > {settings_tolerance:.0%}")
        v = f"depends on the embedding settings ({why})"
    elif not converged:
        v = (f"not converged (the running estimate moved over {SETTLED:.0%} over the second half)" if not settled
             else f"not converged (fewer than 2 of {win.size} windows long enough for these settings)"
             if not np.isfinite(u) else f"not converged (standard error {u:.2g} 1/s over {int(ok.sum())} "
                  f"{'members' if members is not None else 'windows'} > {WINDOW_RESOLVED:.0%} of {e_main:.4g})")
    else:
        v = "positive" if positive else "not positive"
    settings = {"dim": dim, "delay": delay, "evolve": evolve, "theiler": theiler, "fnn_dim": fnn.minimum_dim,
                "n_surrogates": int(n_surrogates), "surrogate": surrogate, "seed": seed}
    out = LyapunovAssessment(method=method, exponent=e_main, result=res, settings=settings, false_neighbours=fnn,
                             surrogate_exponents=se, surrogate_z=float(z), distinguishable=distinguishable,
                             grid=grid, settings_spread=spread, insensitive=insensitive, window_exponents=win,
                             uncertainty=u, converged=converged, verdict=v)
    logger.info("assess_largest_lyapunov (%s): %.4g 1/s, %s", method, e_main, v)
    return out
